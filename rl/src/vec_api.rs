//! What PPO needs from a batch of environments: flat `f32` observations and actions.

/// One batched step.
#[derive(Clone, Debug, Default)]
pub struct StepBatch {
    /// Next observations (after an auto-reset, the new episode's first one), `[env][obs_dim]`.
    pub obs: Vec<Vec<f32>>,
    pub rewards: Vec<f32>,
    pub terminated: Vec<bool>,
    pub truncated: Vec<bool>,
    /// For episodes that ended this step, their last observation (to bootstrap truncations).
    pub final_obs: Vec<Option<Vec<f32>>>,
    /// For episodes that ended this step: success, return and length.
    pub finished: Vec<Option<EpisodeStats>>,
}

/// Summary of a finished episode.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct EpisodeStats {
    pub success: bool,
    pub episode_return: f32,
    pub length: usize,
}

/// A batch of auto-resetting environments.
pub trait VecEnvironment {
    fn n_envs(&self) -> usize;
    fn obs_dim(&self) -> usize;
    fn act_dim(&self) -> usize;
    /// Resets every environment.
    fn reset(&mut self) -> Vec<Vec<f32>>;
    /// Steps every environment with the policy's raw actions (the env clips them).
    fn step(&mut self, actions: &[Vec<f32>]) -> StepBatch;
}
