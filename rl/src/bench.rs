//! `bench ppo`: how fast PPO updates (on an environment that costs nothing), and how fast it
//! trains on the grasp env.

use std::time::Instant;

use burn::tensor::Device;
use fairgrasp_env::presets;
use serde::Serialize;

use crate::agent::grasp_agent::{ACT_DIM, AgentConfig};
use crate::agent::grasp_env::GraspVecEnv;
use crate::ppo::model::{ActorCritic, ModelConfig};
use crate::ppo::normalizer::RunningNorm;
use crate::ppo::vec_api::{EpisodeStats, StepBatch, VecEnvError, VecEnvironment};
use crate::ppo::{Ppo, PpoConfig, PpoError};

/// An environment that costs nothing: deterministic made-up observations, reward 0.01 per step,
/// every episode cut after 200 steps; so an iteration on it times PPO alone.
pub struct FreeEnv {
    dim: usize,
    t: u64,
    batch: StepBatch,
}

impl FreeEnv {
    /// `n` environments with `dim` inputs and [`ACT_DIM`] actions.
    pub fn new(n: usize, dim: usize) -> Self {
        let mut env = Self {
            dim,
            t: 0,
            batch: StepBatch::new(n, dim),
        };
        env.fill_obs();
        env
    }

    /// Observation value `((t + 7·e + d) mod 13) · 0.1` of env `e`, dimension `d`.
    fn fill_obs(&mut self) {
        let dim = self.dim.max(1);
        for (k, o) in self.batch.obs.iter_mut().enumerate() {
            let (e, d) = (k / dim, k % dim);
            *o = ((self.t as usize + e * 7 + d) % 13) as f32 * 0.1;
        }
    }
}

impl VecEnvironment for FreeEnv {
    fn n_envs(&self) -> usize {
        self.batch.rewards.len()
    }
    fn obs_dim(&self) -> usize {
        self.dim
    }
    fn act_dim(&self) -> usize {
        ACT_DIM
    }
    fn reset(&mut self) -> Result<&[f32], VecEnvError> {
        self.fill_obs();
        Ok(&self.batch.obs)
    }
    fn step(&mut self, _actions: &[f32]) -> Result<&StepBatch, VecEnvError> {
        self.t += 1;
        let done = self.t.is_multiple_of(200);
        let b = &mut self.batch;
        b.rewards.fill(0.01);
        b.terminated.fill(false);
        b.truncated.fill(done);
        b.final_obs.fill(0.0);
        b.finished.fill(done.then(EpisodeStats::default));
        self.fill_obs();
        Ok(&self.batch)
    }
}

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
    /// One iteration (rollout + update) on [`FreeEnv`] [s].
    pub ppo_iteration_s_without_env: f64,
    /// The preset (or config file) the training phase ran on.
    pub preset: String,
    /// Env steps per second of training on the grasp env (residual agent, `preset`).
    pub train_env_steps_per_s: f64,
    /// One iteration on the grasp env [s].
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

    let mut free = FreeEnv::new(n_envs, dim);
    let mut p = ppo(&config, dim);
    p.iterate(&mut free, 0.0)?; // warm-up
    let t = Instant::now();
    for k in 0..iterations {
        p.iterate(&mut free, k as f64 / iterations as f64)?;
    }
    let ppo_s = t.elapsed().as_secs_f64() / iterations as f64;

    let env_config = presets::load(preset)?;
    let mut env = GraspVecEnv::new(&env_config, agent, n_envs, 2, 0)?;
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
