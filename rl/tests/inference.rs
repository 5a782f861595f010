//! The burn-free actor (`fairgrasp-policy`) computes the shipped policies' mean actions as burn's
//! forward pass does, to 1e-5, on inputs across the normalised range.

use burn::tensor::{Device, Tensor, TensorData};
use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::burnpack::read_tensors;
use fairgrasp_rl::agent::Mode;
use fairgrasp_rl::run::checkpoint::load_model;
use fairgrasp_rl::run::shipped::ShippedPolicy;
use fairgrasp_rl::run::train::TrainConfig;
use fairgrasp_types::paired::mcnemar_exact;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

#[test]
fn every_shipped_policy_acts_the_same_without_burn_to_1e_5() {
    let device = Device::flex();
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    for policy in ShippedPolicy::ALL {
        let dir = policy.checkpoint_dir().unwrap();
        let (meta, model) = load_model(&dir, &device).unwrap();
        let bytes = std::fs::read(dir.join("model.bpk")).unwrap();
        let mut sizes = vec![meta.input_dim];
        sizes.extend(&meta.model.hidden);
        sizes.push(meta.act_dim);
        let actor = Actor::from_tensors(&read_tensors(&bytes).unwrap(), &sizes).unwrap();
        let mut worst = 0.0f32;
        for _ in 0..200 {
            // Normalised inputs lie in ±10; most within ±3.
            let x: Vec<f32> = (0..meta.input_dim)
                .map(|_| rng.random_range(-3.0f32..3.0))
                .collect();
            let input = Tensor::<2>::from_data(TensorData::new(x.clone(), [1, x.len()]), &device);
            let burn: Vec<f32> = model.mean(input).into_data().try_to_vec().unwrap();
            let ours = actor.mean(&x);
            assert_eq!(burn.len(), ours.len());
            for (a, b) in burn.iter().zip(&ours) {
                worst = worst.max((a - b).abs());
            }
        }
        eprintln!("{}: largest difference {worst:e}", policy.name());
        assert!(worst <= 1e-5, "{}: {worst}", policy.name());
    }
}

/// A checkpoint's deterministic policy through burn's forward pass (what training's evaluations
/// ran before they ran the burn-free actor, `agent_policy`).
fn burn_policy(
    meta: &fairgrasp_rl::run::checkpoint::CheckpointMeta,
    model: &fairgrasp_rl::ppo::model::ActorCritic,
    env: &fairgrasp_env::EnvConfig,
) -> fairgrasp_rl::agent::GraspAgent {
    let inference = burn::module::Module::valid(model);
    let norm = meta.obs_norm.clone();
    let device = Device::flex();
    let mean = move |x: &[f32]| {
        let input =
            Tensor::<2>::from_data(TensorData::new(norm.normalize(x), [1, x.len()]), &device);
        inference
            .mean(input)
            .into_data()
            .try_to_vec::<f32>()
            .expect("f32 output")
    };
    fairgrasp_rl::agent::GraspAgent::new(meta.agent.clone(), env, Box::new(mean))
}

/// The presets a shipped policy was trained on: its run's `preset`, then `mix` (a generalist's
/// other families).
fn families(policy: ShippedPolicy) -> Vec<String> {
    let dir = policy.checkpoint_dir().unwrap();
    let run = TrainConfig::from_toml_file(&dir.parent().unwrap().join("config.toml")).unwrap();
    std::iter::once(run.preset).chain(run.mix).collect()
}

#[test]
fn every_shipped_policy_ends_300_episodes_the_same_without_burn() {
    use fairgrasp_env::config::presets;
    use fairgrasp_env::episode::evaluate;
    use fairgrasp_env::scenario::scenario_set;
    use fairgrasp_policy::checkpoint::{actor_policy, load_actor};

    let device = Device::flex();
    let each = ShippedPolicy::ALL
        .into_iter()
        .flat_map(|p| families(p).into_iter().map(move |f| (p, f)));
    for (policy, family) in each {
        let dir = policy.checkpoint_dir().unwrap();
        let (meta, model) = load_model(&dir, &device).unwrap();
        let (_, actor) = load_actor(&dir).unwrap();
        let config = presets::load(&family).unwrap();
        let scenarios = scenario_set(&config, 7, 300).unwrap();
        let with_burn = evaluate(
            &config,
            &scenarios,
            2,
            None,
            &|| burn_policy(&meta, &model, &config),
            &|| {},
        )
        .unwrap();
        let without = evaluate(
            &config,
            &scenarios,
            2,
            None,
            &|| actor_policy(&meta, &actor, &config),
            &|| {},
        )
        .unwrap();
        // The two forward passes differ in the last bits (≤ 1e-5). A residual's correction is
        // small, frozen at the close, and the script leads: its outcomes must be identical. A
        // pure policy acts alone every step, and a squeezing residual sets the grip force every
        // step of the grasp: contact can amplify a last-bit difference, so their outcomes may
        // differ on a few episodes, never significantly (McNemar, both ways).
        let pairs: Vec<_> = with_burn.results.iter().zip(&without.results).collect();
        assert_eq!(pairs.len(), 300);
        assert!(pairs.iter().all(|(a, b)| a.seed == b.seed));
        let only = |burn: bool| {
            pairs
                .iter()
                .filter(|(a, b)| a.success() == burn && b.success() != burn)
                .count()
        };
        let (only_burn, only_actor) = (only(true), only(false));
        let other_outcome = pairs.iter().filter(|(a, b)| a.outcome != b.outcome).count();
        let p = mcnemar_exact(only_burn, only_actor);
        eprintln!(
            "{} on {}: {:.1} % with burn, {:.1} % without; {other_outcome} episodes end otherwise \
             ({only_burn} / {only_actor} successes of one only, McNemar p = {p:.3})",
            policy.name(),
            family,
            100.0 * with_burn.success_rate,
            100.0 * without.success_rate,
        );
        if meta.agent.mode == Mode::Residual && !meta.agent.squeeze {
            assert_eq!(other_outcome, 0, "{} on {family}", policy.name());
        }
        assert!(p >= 0.05, "{} on {family}: p = {p}", policy.name());
    }
}
