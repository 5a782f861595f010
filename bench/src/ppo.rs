//! `bench ppo`: how fast PPO updates (on an environment that costs nothing), and how fast it
//! trains on the grasp env.

use std::time::Instant;

use burn::tensor::Device;
use fairgrasp_env::config::presets;
use serde::Serialize;

use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig};
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::free_env::FreeEnv;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::ppo::normalizer::RunningNorm;
use fairgrasp_rl::ppo::{Ppo, PpoConfig, PpoError};

/// What `bench ppo` measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PpoBench {
    pub network: String,
    pub input_dim: usize,
    pub n_envs: usize,
    /// Samples per iteration: `n_steps · n_envs`.
    pub samples_per_iteration: usize,
    pub epochs: usize,
    pub minibatch: usize,
    /// Gradient-step throughput: samples × epochs per second of an iteration on [`FreeEnv`].
    pub update_samples_per_s: f64,
    /// One iteration (rollout + update) on [`FreeEnv`] \[s\].
    pub ppo_iteration_s_without_env: f64,
    /// The preset (or config file) the training phase ran on.
    pub preset: String,
    /// Env steps per second of training on the grasp env (residual agent, `preset`).
    pub train_env_steps_per_s: f64,
    /// One iteration on the grasp env \[s\].
    pub training_iteration_s: f64,
}

/// Why the benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error("iterations must be at least 1")]
    NoIterations,
    #[error(transparent)]
    Preset(#[from] fairgrasp_env::ConfigError),
    #[error(transparent)]
    Env(#[from] fairgrasp_env::EnvError),
    #[error(transparent)]
    Ppo(#[from] PpoError),
}

fn ppo(config: &PpoConfig, dim: usize) -> Ppo {
    let device = Device::flex().autodiff();
    let model = ActorCritic::new(dim, ACT_DIM, &ModelConfig::default(), 0, &device);
    Ppo::new(
        config.clone(),
        model,
        RunningNorm::new(dim, true),
        device,
        0,
    )
}

/// Times `iterations` PPO iterations (after one warm-up) on [`FreeEnv`], then `iterations` on
/// the grasp env of `preset` (a preset name or a `.toml` file; residual agent, 4 envs on 2
/// threads); `n_steps` 512, SB3's other defaults.
pub fn bench_ppo(iterations: u32, preset: &str) -> Result<PpoBench, BenchError> {
    if iterations == 0 {
        return Err(BenchError::NoIterations);
    }
    let agent = AgentConfig::default();
    let dim = agent.input_dim();
    let config = PpoConfig {
        n_steps: 512,
        ..PpoConfig::default()
    };
    let n_envs = 4;
    let samples = config.n_steps * n_envs;

    let mut free = FreeEnv::new(n_envs, dim, ACT_DIM);
    let mut p = ppo(&config, dim);
    p.iterate(&mut free, 0.0)?; // warm-up
    let t = Instant::now();
    for k in 0..iterations {
        p.iterate(&mut free, k as f64 / iterations as f64)?;
    }
    let ppo_s = t.elapsed().as_secs_f64() / iterations as f64;

    let env_config = presets::load(preset)?;
    let mut env = TaskVecEnv::new(&env_config, agent, n_envs, 2, 0)?;
    let mut p = ppo(&config, dim);
    let t = Instant::now();
    for k in 0..iterations {
        p.iterate(&mut env, k as f64 / iterations as f64)?;
    }
    let train_s = t.elapsed().as_secs_f64() / iterations as f64;
    Ok(PpoBench {
        network: "64x64 tanh, separate actor and critic".into(),
        input_dim: dim,
        n_envs,
        samples_per_iteration: samples,
        epochs: config.n_epochs,
        minibatch: config.batch_size,
        update_samples_per_s: samples as f64 * config.n_epochs as f64 / ppo_s,
        ppo_iteration_s_without_env: ppo_s,
        preset: preset.to_string(),
        train_env_steps_per_s: samples as f64 / train_s,
        training_iteration_s: train_s,
    })
}
