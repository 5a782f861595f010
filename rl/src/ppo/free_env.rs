//! An environment that costs nothing, for timing and testing PPO alone.

use crate::ppo::vec_api::{EpisodeStats, StepBatch, VecEnvError, VecEnvironment};

/// An environment that costs nothing: deterministic made-up observations, reward 0.01 per step,
/// every episode cut after 200 steps; so an iteration on it times PPO alone.
pub struct FreeEnv {
    dim: usize,
    act_dim: usize,
    t: u64,
    batch: StepBatch,
}

impl FreeEnv {
    /// `n` environments with `dim` inputs and `act_dim` actions.
    pub fn new(n: usize, dim: usize, act_dim: usize) -> Self {
        let mut env = Self {
            dim,
            act_dim,
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
        self.act_dim
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
