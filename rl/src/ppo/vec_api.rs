//! What PPO needs from a batch of environments: flat `f32` policy inputs and actions, in buffers
//! the environment owns and refills in place every step.

use fairgrasp_env::EnvError;

/// One batched step, rows in environment order. Flat storage: row `e` of a `[env][dim]` field is
/// `field[e * dim..(e + 1) * dim]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepBatch {
    /// Next policy inputs (after an auto-reset, the new episode's first one), `[env][obs_dim]`.
    pub obs: Vec<f32>,
    /// Reward of this step, per env.
    pub rewards: Vec<f32>,
    /// The episode reached a terminal state (no bootstrap), per env.
    pub terminated: Vec<bool>,
    /// The episode was cut (time limit, fault): bootstrap from `final_obs`, per env.
    pub truncated: Vec<bool>,
    /// `[env][obs_dim]`: for an env whose episode ended this step (terminated or truncated),
    /// the policy input of its last observation; other rows hold nothing meaningful.
    pub final_obs: Vec<f32>,
    /// For episodes that ended this step: success, return and length.
    pub finished: Vec<Option<EpisodeStats>>,
}

impl StepBatch {
    /// A batch for `n_envs` environments with `obs_dim` inputs each, zero-filled.
    pub fn new(n_envs: usize, obs_dim: usize) -> Self {
        Self {
            obs: vec![0.0; n_envs * obs_dim],
            rewards: vec![0.0; n_envs],
            terminated: vec![false; n_envs],
            truncated: vec![false; n_envs],
            final_obs: vec![0.0; n_envs * obs_dim],
            finished: vec![None; n_envs],
        }
    }

    /// Checks that every field holds `n_envs` rows of `obs_dim` (or one value per env).
    pub fn check_shape(&self, n_envs: usize, obs_dim: usize) -> Result<(), VecEnvError> {
        let per_env = n_envs * obs_dim;
        [
            ("observation", per_env, self.obs.len()),
            ("final observation", per_env, self.final_obs.len()),
            ("reward", n_envs, self.rewards.len()),
            ("terminated", n_envs, self.terminated.len()),
            ("truncated", n_envs, self.truncated.len()),
            ("finished", n_envs, self.finished.len()),
        ]
        .into_iter()
        .find(|&(_, expected, got)| expected != got)
        .map_or(Ok(()), |(what, expected, got)| {
            Err(VecEnvError::Shape {
                what,
                expected,
                got,
            })
        })
    }

    /// Did environment `e`'s episode end in this step?
    pub fn ended(&self, e: usize) -> bool {
        self.terminated[e] || self.truncated[e]
    }
}

/// Summary of a finished episode.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct EpisodeStats {
    pub success: bool,
    /// How the episode ended, for tasks that name it (the grasp env's record: its
    /// `fairgrasp_types::EpisodeRecord::outcome`).
    pub outcome: Option<fairgrasp_types::Outcome>,
    /// Sum of the episode's rewards.
    pub episode_return: f32,
    /// Steps \[env steps\].
    pub length: usize,
    /// Where the episode's cube started, table frame \[m\] (None where there is no cube).
    pub object_xy: Option<[f64; 2]>,
}

/// Why a batch of environments could not reset or step.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VecEnvError {
    #[error("the environment failed: {0}")]
    Env(#[from] EnvError),
    #[error(
        "{got} action values for {n_envs} environments × {act_dim}: expected {}",
        .n_envs * .act_dim
    )]
    ActionShape {
        n_envs: usize,
        act_dim: usize,
        got: usize,
    },
    #[error("the environment returned {got} {what} values, expected {expected}")]
    Shape {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    #[error("environment {env}: {what}[{index}] = {value} is not finite")]
    NonFinite {
        env: usize,
        what: &'static str,
        index: usize,
        value: f32,
    },
}

/// A batch of auto-resetting environments.
pub trait VecEnvironment {
    fn n_envs(&self) -> usize;
    /// Size of one policy input.
    fn obs_dim(&self) -> usize;
    /// Size of one action.
    fn act_dim(&self) -> usize;
    /// Resets every environment; returns the policy inputs, `[env][obs_dim]` flat.
    fn reset(&mut self) -> Result<&[f32], VecEnvError>;
    /// Steps every environment with the policy's raw actions, `[env][act_dim]` flat (the env
    /// clips them). The batch is the environment's own buffer, refilled by the next call.
    fn step(&mut self, actions: &[f32]) -> Result<&StepBatch, VecEnvError>;
}

/// The first non-finite value of `[env][dim]` rows, as an error naming `what`.
pub fn check_finite(rows: &[f32], dim: usize, what: &'static str) -> Result<(), VecEnvError> {
    match rows.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(VecEnvError::NonFinite {
            env: i / dim.max(1),
            what,
            index: i % dim.max(1),
            value: rows[i],
        }),
    }
}
