//! The rollout buffer: one preallocated flat buffer per quantity, as CleanRL keeps one tensor per
//! quantity. Sample `i = t · n_envs + e` (step-major) of a `[sample][dim]` quantity is
//! `q[i * dim..(i + 1) * dim]`; minibatches gather the rows they index, nothing is cloned per
//! sample.

use crate::ppo::gae::compute_gae_into;
use crate::ppo::vec_api::EpisodeStats;

/// Sizes of a rollout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RolloutShape {
    /// Steps per environment.
    pub n_steps: usize,
    pub n_envs: usize,
    /// Policy input size.
    pub obs_dim: usize,
    pub act_dim: usize,
}

impl RolloutShape {
    /// Samples in a rollout: `n_steps · n_envs`.
    pub fn samples(&self) -> usize {
        self.n_steps * self.n_envs
    }
}

/// One rollout's storage. Filled by PPO's collection, read by its update.
#[derive(Clone, Debug)]
pub struct RolloutBuffer {
    pub shape: RolloutShape,
    /// Normalised policy inputs `[sample][obs_dim]` (as the network saw them).
    pub obs: Vec<f32>,
    /// Sampled actions `[sample][act_dim]` (before the env clips them).
    pub actions: Vec<f32>,
    /// Log-probability of each action when it was sampled `[sample]`.
    pub logprobs: Vec<f32>,
    pub rewards: Vec<f32>,
    /// The episode ended in a terminal state after this sample (no bootstrap).
    pub terminated: Vec<bool>,
    /// The episode was cut after this sample (bootstrap from `final_values`).
    pub truncated: Vec<bool>,
    /// Critic values `V(s_t)` `[sample]`.
    pub values: Vec<f32>,
    /// `V` of an ended episode's last observation `[sample]` (0 where none ended).
    pub final_values: Vec<f32>,
    /// `V` of the observation after the rollout's last step `[env]`.
    pub next_values: Vec<f32>,
    /// GAE advantages `[sample]`.
    pub advantages: Vec<f32>,
    /// Value targets `A + V` `[sample]`.
    pub returns: Vec<f32>,
    /// Episodes that finished during the rollout.
    pub episodes: Vec<EpisodeStats>,
}

impl RolloutBuffer {
    /// Zero-filled storage for `shape`.
    pub fn new(shape: RolloutShape) -> Self {
        let n = shape.samples();
        Self {
            shape,
            obs: vec![0.0; n * shape.obs_dim],
            actions: vec![0.0; n * shape.act_dim],
            logprobs: vec![0.0; n],
            rewards: vec![0.0; n],
            terminated: vec![false; n],
            truncated: vec![false; n],
            values: vec![0.0; n],
            final_values: vec![0.0; n],
            next_values: vec![0.0; shape.n_envs],
            advantages: vec![0.0; n],
            returns: vec![0.0; n],
            episodes: Vec::new(),
        }
    }

    /// The range of samples of step `t`: `t · n_envs .. (t + 1) · n_envs`.
    pub fn step_range(&self, t: usize) -> std::ops::Range<usize> {
        t * self.shape.n_envs..(t + 1) * self.shape.n_envs
    }

    /// Fills `advantages` and `returns` with GAE(γ, λ).
    pub fn compute_advantages(&mut self, gamma: f32, lambda: f32) {
        compute_gae_into(
            self.shape.n_envs,
            &self.rewards,
            &self.values,
            &self.terminated,
            &self.truncated,
            &self.final_values,
            &self.next_values,
            gamma,
            lambda,
            &mut self.advantages,
            &mut self.returns,
        );
    }
}

/// Rows `indices` of the `[sample][dim]` quantity `source`, concatenated.
pub fn gather_rows(source: &[f32], dim: usize, indices: &[usize]) -> Vec<f32> {
    let mut out = Vec::with_capacity(indices.len() * dim);
    for &i in indices {
        out.extend_from_slice(&source[i * dim..(i + 1) * dim]);
    }
    out
}

/// `source[i]` for each of `indices`.
pub fn gather(source: &[f32], indices: &[usize]) -> Vec<f32> {
    indices.iter().map(|&i| source[i]).collect()
}
