//! A model as a deterministic policy, and its evaluation on a fixed scenario set.

use fairgrasp_env::EnvConfig;
use fairgrasp_env::episode::{EvalReport, evaluate_seeded};
use fairgrasp_policy::checkpoint::actor_policy;
use fairgrasp_policy::recipe::EnvFor;

use crate::agent::grasp_agent::GraspAgent;
use crate::ppo::model::ActorCritic;
use crate::run::checkpoint::CheckpointMeta;
use crate::run::config::TrainConfig;
use crate::run::error::TrainError;

/// Seed of the scenario set a training run is evaluated on; training scenarios never use it.
pub const EVAL_SEED: u64 = 1_000_000;

/// Evaluates a model deterministically on `n` scenarios of the run's preset (seed
/// [`EVAL_SEED`]); a run on several presets (`mix`) splits the `n` over them, the first
/// `n % presets` getting one more, and reports them together.
pub fn evaluate_model(
    config: &TrainConfig,
    meta: &CheckpointMeta,
    model: &ActorCritic,
    n: usize,
) -> Result<EvalReport, TrainError> {
    let env_configs = config
        .env_configs(EnvFor::Evaluation)
        .map_err(TrainError::Config)?;
    let k = env_configs.len();
    let actor = model.plain_actor();
    let mut results = Vec::with_capacity(n);
    for (j, env_config) in env_configs.iter().enumerate() {
        let share = n / k + usize::from(j < n % k);
        if share == 0 {
            continue;
        }
        let make = || actor_policy(meta, &actor, env_config);
        let report = evaluate_seeded(
            env_config,
            EVAL_SEED,
            share,
            config.threads,
            None,
            &make,
            &|| {},
        )?;
        results.extend(report.results);
    }
    Ok(EvalReport::from_results(results))
}

/// The deterministic agent policy of a checkpoint's model: the burn-free actor users run
/// ([`actor_policy`], what `eval` and `compare` load from `model.bpk`), on the model's weights.
pub fn agent_policy(meta: &CheckpointMeta, model: &ActorCritic, env: &EnvConfig) -> GraspAgent {
    actor_policy(meta, &model.plain_actor(), env)
}
