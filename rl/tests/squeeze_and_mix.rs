//! The squeeze (a task-space residual's entry 4 commands the grip force) reaches the envs PPO
//! trains on, and a run on several presets (`mix`) steps each env on its own preset and is
//! checked before it starts.

use fairgrasp_env::config::{ActionSpace, presets};
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig, Mode};
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::vec_api::VecEnvironment;
use fairgrasp_rl::run::train::TrainConfig;

fn squeezing() -> AgentConfig {
    AgentConfig {
        mode: Mode::Residual,
        action_space: ActionSpace::Tcp,
        squeeze: true,
        ..AgentConfig::default()
    }
}

/// Success rate of the finished episodes of a constant policy output over `steps` steps.
fn constant_output_success(agent: AgentConfig, squeeze: f32, steps: usize) -> (usize, usize) {
    let config = presets::load("heavy_slippery").unwrap();
    let n = 8;
    let mut env = TaskVecEnv::new(&config, agent, n, 2, 11).unwrap();
    env.reset().unwrap();
    let mut action = vec![0.0f32; n * ACT_DIM];
    for e in 0..n {
        action[e * ACT_DIM + 4] = squeeze;
    }
    let (mut done, mut lifted) = (0, 0);
    for _ in 0..steps {
        let batch = env.step(&action).unwrap();
        for stats in batch.finished.iter().flatten() {
            done += 1;
            lifted += usize::from(stats.success);
        }
    }
    (lifted, done)
}

#[test]
fn a_full_squeeze_lifts_the_heavy_slippery_cubes_in_training_envs_and_no_squeeze_does_not() {
    let (held, n_held) = constant_output_success(squeezing(), 1.0, 1000);
    let (plain, n_plain) = constant_output_success(squeezing(), 0.0, 1000);
    // Without `squeeze`, entry 4 is unused: a full command there changes nothing.
    let (unused, n_unused) = constant_output_success(
        AgentConfig {
            squeeze: false,
            ..squeezing()
        },
        1.0,
        1000,
    );
    eprintln!("squeeze +1: {held}/{n_held}, 0: {plain}/{n_plain}, unused: {unused}/{n_unused}");
    assert!(n_held >= 40 && n_plain >= 40, "{n_held} {n_plain}");
    assert!(held * 100 >= 90 * n_held, "{held}/{n_held}");
    assert!(plain * 100 <= 60 * n_plain, "{plain}/{n_plain}");
    assert_eq!((unused, n_unused), (plain, n_plain));
}

#[test]
fn a_mixed_run_steps_each_env_on_its_own_preset() {
    let light = presets::load("full").unwrap();
    let heavy = presets::load("heavy_slippery").unwrap();
    let mut env = TaskVecEnv::mixed(&[light.clone(), heavy.clone()], squeezing(), 6, 2, 3).unwrap();
    env.reset().unwrap();
    let batch = env.inner_mut().batch();
    let masses: Vec<f64> = batch
        .infos
        .iter()
        .map(|i| i.scenario.unwrap().mass)
        .collect();
    // `full` draws 0.08–0.12 kg, `heavy_slippery` 0.3–1.0 kg: envs 0, 2, 4 and 1, 3, 5.
    for (e, m) in masses.iter().enumerate() {
        if e % 2 == 0 {
            assert!(*m < 0.2, "env {e}: {m} kg");
        } else {
            assert!(*m > 0.25, "env {e}: {m} kg");
        }
    }
}

#[test]
fn a_mixed_run_is_checked_before_it_starts() {
    let base = TrainConfig {
        preset: "full".into(),
        mix: vec!["nudged".into(), "heavy_slippery".into()],
        agent: squeezing(),
        n_envs: 6,
        ..TrainConfig::default()
    };
    base.validate().unwrap();
    let few = TrainConfig {
        n_envs: 2,
        ..base.clone()
    };
    let e = few.validate().unwrap_err().to_string();
    assert!(e.contains("mix") && e.contains("n_envs ≥ 3"), "{e}");
    let unknown = TrainConfig {
        mix: vec!["nudgd".into()],
        ..base.clone()
    };
    let e = unknown.validate().unwrap_err().to_string();
    assert!(e.contains("mix: nudgd"), "{e}");
    let staged = TrainConfig {
        curriculum: Some(Default::default()),
        ..base.clone()
    };
    let e = staged.validate().unwrap_err().to_string();
    assert!(e.contains("mix") && e.contains("curriculum"), "{e}");
    let joint = TrainConfig {
        agent: AgentConfig {
            action_space: ActionSpace::Joint,
            ..squeezing()
        },
        ..base
    };
    let e = joint.validate().unwrap_err().to_string();
    assert!(e.contains("squeeze") && e.contains("tcp"), "{e}");
}
