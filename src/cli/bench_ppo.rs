//! `fairgrasp bench ppo`: how fast PPO updates, and how fast it trains on the grasp env.

use std::process::ExitCode;
use std::time::Instant;

use burn::tensor::Device;
use fairgrasp_env::presets;
use fairgrasp_rl::agent::{ACT_DIM, AgentConfig};
use fairgrasp_rl::grasp_env::GraspVecEnv;
use fairgrasp_rl::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::normalizer::RunningNorm;
use fairgrasp_rl::ppo::{Ppo, PpoConfig};
use fairgrasp_rl::vec_api::{EpisodeStats, StepBatch, VecEnvironment};
use serde_json::json;

/// An environment that costs nothing: random observations, so an iteration times PPO alone.
struct FreeEnv {
    n: usize,
    dim: usize,
    t: u64,
}

impl VecEnvironment for FreeEnv {
    fn n_envs(&self) -> usize {
        self.n
    }
    fn obs_dim(&self) -> usize {
        self.dim
    }
    fn act_dim(&self) -> usize {
        ACT_DIM
    }
    fn reset(&mut self) -> Vec<Vec<f32>> {
        self.obs()
    }
    fn step(&mut self, _actions: &[Vec<f32>]) -> StepBatch {
        self.t += 1;
        let done = self.t.is_multiple_of(200);
        StepBatch {
            obs: self.obs(),
            rewards: vec![0.01; self.n],
            terminated: vec![false; self.n],
            truncated: vec![done; self.n],
            final_obs: vec![done.then(|| vec![0.0; self.dim]); self.n],
            finished: vec![done.then(EpisodeStats::default); self.n],
        }
    }
}

impl FreeEnv {
    fn obs(&self) -> Vec<Vec<f32>> {
        (0..self.n)
            .map(|e| {
                (0..self.dim)
                    .map(|d| ((self.t as usize + e * 7 + d) % 13) as f32 * 0.1)
                    .collect()
            })
            .collect()
    }
}

fn ppo(config: &PpoConfig, dim: usize) -> Ppo {
    let device = Device::flex().autodiff();
    device.seed(0);
    let model = ActorCritic::new(dim, ACT_DIM, &ModelConfig::default(), &device);
    Ppo::new(
        config.clone(),
        model,
        RunningNorm::new(dim, true),
        device,
        0,
    )
}

/// Peak resident set size of this process [MB] (getrusage `ru_maxrss`, kB on Linux).
pub fn peak_rss_mb() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes a complete rusage into the pointer it is given.
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    usage.ru_maxrss as f64 / 1024.0
}

pub fn run(iterations: u32, as_json: bool) -> anyhow::Result<ExitCode> {
    let agent = AgentConfig::default();
    let dim = agent.input_dim();
    let config = PpoConfig {
        n_steps: 512,
        ..PpoConfig::default()
    };
    let n_envs = 4;
    let samples = (config.n_steps * n_envs) as f64;

    // PPO alone: rollout on a free env, then the update.
    let mut free = FreeEnv {
        n: n_envs,
        dim,
        t: 0,
    };
    let mut p = ppo(&config, dim);
    p.iterate(&mut free, 0.0); // warm-up
    let t = Instant::now();
    for k in 0..iterations {
        p.iterate(&mut free, k as f64 / iterations as f64);
    }
    let ppo_s = t.elapsed().as_secs_f64() / iterations as f64;
    let update_samples_per_s = samples * config.n_epochs as f64 / ppo_s;

    // Training on the grasp env (residual agent, `hard` preset, 2 threads).
    let env_config = presets::load("hard")?;
    let mut env = GraspVecEnv::new(&env_config, agent, n_envs, 2, 0)?;
    let mut p = ppo(&config, dim);
    let t = Instant::now();
    for k in 0..iterations {
        p.iterate(&mut env, k as f64 / iterations as f64);
    }
    let train_s = t.elapsed().as_secs_f64() / iterations as f64;
    let out = json!({
        "network": "64x64 tanh, separate actor and critic",
        "input_dim": dim,
        "samples_per_iteration": samples,
        "epochs": config.n_epochs,
        "minibatch": config.batch_size,
        "update_samples_per_s": update_samples_per_s,
        "ppo_iteration_s_without_env": ppo_s,
        "train_env_steps_per_s": samples / train_s,
        "training_iteration_s": train_s,
        "peak_rss_mb": peak_rss_mb(),
    });
    if as_json {
        println!("{out}");
    } else {
        println!(
            "PPO, 64×64 actor and critic, input {dim}, {samples} samples × {} epochs, minibatch {}",
            config.n_epochs, config.batch_size
        );
        println!(
            "  update throughput        {update_samples_per_s:>10.0} samples/s (gradient steps over samples)"
        );
        println!("  iteration without env    {ppo_s:>10.3} s");
        println!(
            "  training with the env    {:>10.0} env steps/s (residual agent, hard preset, 4 envs, 2 threads)",
            samples / train_s
        );
        println!("  peak resident memory     {:>10.1} MB", peak_rss_mb());
    }
    Ok(ExitCode::SUCCESS)
}
