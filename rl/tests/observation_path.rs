//! Training and evaluation feed the baseline the same typed observation: the vectorised training
//! path (`TaskVecEnv`) and the single-env evaluation path (`TaskEnv` + `ScriptedGrasp`), on the
//! same scenario seeds with the same actions, give bit-identical baseline actions and policy
//! inputs, at every step, at episode ends and after auto-resets.

use fairgrasp_env::episode::Policy;
use fairgrasp_env::{Action, EnvConfig, TaskEnv, config::presets};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig};
use fairgrasp_rl::agent::script::Script;
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::vec_api::VecEnvironment;

const N_ENVS: usize = 2;
const BASE_SEED: u64 = 40;
/// Steps per episode (short, so that episodes end and auto-reset within the test).
const MAX_STEPS: usize = 30;
const STEPS: usize = 75;

/// What one path saw for one env: per step, the baseline's action and the policy input;
/// per ended episode, the same for its final observation.
#[derive(Debug, Default, PartialEq)]
struct Trace {
    actions: Vec<Action>,
    inputs: Vec<Vec<f32>>,
    final_actions: Vec<Action>,
    final_inputs: Vec<Vec<f32>>,
}

fn config() -> EnvConfig {
    // Random position and yaw: yaws beyond ±45° are where a flattened observation (yaw modulo
    // 90°) and the true one part.
    let mut c = presets::load("full").unwrap();
    c.task.max_steps = MAX_STEPS;
    c
}

fn training_path(config: &EnvConfig, agent: &AgentConfig) -> Vec<Trace> {
    let dim = agent.input_dim();
    let mut env = TaskVecEnv::new(config, agent.clone(), N_ENVS, 2, BASE_SEED).unwrap();
    let mut traces: Vec<Trace> = (0..N_ENVS).map(|_| Trace::default()).collect();
    let first = env.reset().unwrap().to_vec();
    let record = |traces: &mut Vec<Trace>, env: &TaskVecEnv, inputs: &[f32]| {
        for (e, t) in traces.iter_mut().enumerate() {
            t.actions.push(env.baseline_action(e).unwrap());
            t.inputs.push(inputs[e * dim..(e + 1) * dim].to_vec());
        }
    };
    record(&mut traces, &env, &first);
    // A zero residual: the envs receive exactly the baseline's actions, as in evaluation.
    let zeros = vec![0.0f32; N_ENVS * ACT_DIM];
    for _ in 0..STEPS {
        let batch = env.step(&zeros).unwrap().clone();
        for (e, t) in traces.iter_mut().enumerate() {
            if batch.ended(e) {
                let row = batch.final_obs[e * dim..(e + 1) * dim].to_vec();
                // The baseline's part of the input is its action as f32.
                let action: [f32; ACT_DIM] = row[dim - ACT_DIM..].try_into().unwrap();
                t.final_actions.push(Action(action.map(f64::from)));
                t.final_inputs.push(row);
            }
        }
        record(&mut traces, &env, &batch.obs);
    }
    traces
}

/// The evaluation path for env `e`: one `TaskEnv`, its episodes' seeds as the vectorised env
/// draws them (`BASE_SEED + e · 1 000 000 + k`), the baseline acting on the env's observation.
fn evaluation_path(config: &EnvConfig, agent: &AgentConfig, e: usize) -> Trace {
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let mut baseline = ScriptedGrasp::new(config, BaselineConfig::default());
    // The input's baseline part comes from the action passed in; this one never acts.
    let joint = Script::joint(config);
    let mut trace = Trace::default();
    let mut episode = 0;
    let start = |env: &mut TaskEnv, baseline: &mut ScriptedGrasp, episode: &mut u64| {
        let seed = BASE_SEED + e as u64 * 1_000_000 + *episode;
        *episode += 1;
        baseline.reset(seed);
        env.reset(seed).unwrap().0
    };
    let mut obs = start(&mut env, &mut baseline, &mut episode);
    for _ in 0..=STEPS {
        let action = baseline.act(&obs);
        trace.actions.push(action);
        trace
            .inputs
            .push(agent.input(&obs, Some(&joint), Some(&action)));
        if trace.actions.len() > STEPS {
            break;
        }
        let step = env.step(&action).unwrap();
        obs = step.obs;
        if step.terminated || step.truncated {
            let last = baseline.act(&step.obs);
            // The training path hands the final action on as f32 inside the input.
            trace
                .final_actions
                .push(Action(last.0.map(|v| v as f32 as f64)));
            trace
                .final_inputs
                .push(agent.input(&step.obs, Some(&joint), Some(&last)));
            obs = start(&mut env, &mut baseline, &mut episode);
        }
    }
    trace
}

#[test]
fn the_baseline_acts_on_the_same_observation_in_training_and_in_evaluation() {
    let config = config();
    let agent = AgentConfig::default();
    let training = training_path(&config, &agent);
    for (e, trained) in training.iter().enumerate() {
        let evaluated = evaluation_path(&config, &agent, e);
        assert_eq!(trained.actions.len(), STEPS + 1);
        assert!(
            trained.final_actions.len() >= 2,
            "env {e}: the test must cross episode ends ({} ended)",
            trained.final_actions.len()
        );
        for (t, (a, b)) in trained.actions.iter().zip(&evaluated.actions).enumerate() {
            let bits = |x: &Action| x.0.map(f64::to_bits);
            assert_eq!(
                bits(a),
                bits(b),
                "env {e} step {t}: training {a:?} vs evaluation {b:?}"
            );
        }
        assert_eq!(trained.inputs, evaluated.inputs, "env {e}: policy inputs");
        assert_eq!(
            trained.final_actions, evaluated.final_actions,
            "env {e}: baseline actions on the episodes' final observations"
        );
        assert_eq!(
            trained.final_inputs, evaluated.final_inputs,
            "env {e}: final policy inputs"
        );
    }
}
