//! Errors, not panics: a diverging run stops with an error naming the update and leaves a
//! loadable, finite `checkpoints/latest`; a non-finite action is refused naming the env.

use burn::tensor::Device;
use fairgrasp_env::config::presets;
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig};
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::PpoConfig;
use fairgrasp_rl::ppo::vec_api::{VecEnvError, VecEnvironment};
use fairgrasp_rl::run::checkpoint;
use fairgrasp_rl::run::train::{TrainConfig, TrainError, train};

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-rl-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn a_diverging_run_stops_with_the_update_and_keeps_a_loadable_finite_latest() {
    let dir = temp_dir("diverge");
    let config = TrainConfig {
        preset: "fixed".into(),
        total_timesteps: 640,
        n_envs: 2,
        threads: 1,
        eval_every: 0,
        eval_episodes: 1,
        // A genuine divergence: the entropy bonus dominates the loss and Adam at learning rate 1
        // raises log σ by about 1 per minibatch step (20 per update), until σ = e^log σ
        // overflows and the sampled actions are infinite.
        ppo: PpoConfig {
            n_steps: 16,
            batch_size: 16,
            n_epochs: 10,
            learning_rate: 1.0,
            ent_coef: 100.0,
            ..PpoConfig::default()
        },
        model: fairgrasp_rl::ppo::model::ModelConfig {
            log_std_init: 2.0,
            ..TrainConfig::default().model
        },
        ..TrainConfig::default()
    };
    let mut reported = 0;
    let err = train(&config, &dir, false, &mut |_| reported += 1).unwrap_err();
    let message = err.to_string();
    let TrainError::Update {
        update, last_good, ..
    } = err
    else {
        panic!("not an update error: {message}");
    };
    assert_eq!(last_good + 1, update, "{message}");
    assert_eq!(
        reported as u64, last_good,
        "updates reported before the failure"
    );
    assert!(
        message.contains(&format!("update {update} failed")) && message.contains("diverged"),
        "{message}"
    );
    let latest = dir.join("checkpoints/latest");
    let (meta, model) = checkpoint::load_model(&latest, &Device::flex()).unwrap();
    assert_eq!(meta.updates, last_good);
    assert!(model.parameters_finite(), "latest holds a diverged network");
    let rows = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    assert_eq!(rows.lines().count() as u64, 1 + last_good, "{rows}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_non_finite_action_is_refused_naming_the_env() {
    let config = presets::load("fixed").unwrap();
    let mut env = TaskVecEnv::new(&config, AgentConfig::default(), 2, 1, 0).unwrap();
    env.reset().unwrap();
    let mut actions = vec![0.0f32; 2 * ACT_DIM];
    actions[ACT_DIM + 3] = f32::NAN;
    let err = env.step(&actions).unwrap_err();
    assert!(
        matches!(
            err,
            VecEnvError::NonFinite {
                env: 1,
                what: "action",
                index: 3,
                ..
            }
        ),
        "{err}"
    );
    let err = env.step(&actions[..ACT_DIM]).unwrap_err();
    assert!(err.to_string().contains("expected 14"), "{err}");
    // The batch is still usable after a refused step.
    assert!(env.step(&[0.0; 2 * ACT_DIM]).is_ok());
}
