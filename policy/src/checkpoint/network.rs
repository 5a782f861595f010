//! The network's shape as a checkpoint records it (`meta.json`'s `model`), and the one rule for
//! what shapes a training config or a checkpoint may have.

use fairgrasp_env::env::spaces::ACT_DIM;
use serde::{Deserialize, Serialize};

/// The most hidden layers a network may have.
pub const MAX_LAYERS: usize = 8;
/// The widest hidden layer a network may have: a 4096 × 4096 layer is 64 MB of f32 weights
/// plus Adam's two moments; wider networks do not fit this kind of machine's training loop.
pub const MAX_WIDTH: usize = 4096;

/// Sizes and initialisation of the network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ModelConfig {
    /// Hidden layer widths of both MLPs (SB3's default 64, 64).
    pub hidden: Vec<usize>,
    /// Initial log standard deviation of the action distribution.
    pub log_std_init: f32,
    /// Initialise the actor's output layer to zero, so the mean action starts at exactly 0
    /// (the residual agent then starts exactly at the baseline).
    pub zero_actor_output: bool,
    /// Initial bias of the actor's output layer, one per action entry in the env's order
    /// (`ACT_NAMES` or `TCP_ACT_NAMES` of `fairgrasp_env::env::spaces`: the gripper last), each
    /// in [−1, 1] (the action range); empty: all 0. It moves the mean action training starts
    /// from: e.g. −0.5 on a pure agent's binary gripper, open on most steps while it explores.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub actor_output_bias: Vec<f32>,
}

impl Default for ModelConfig {
    fn default() -> Self {
        Self {
            hidden: vec![64, 64],
            log_std_init: 0.0,
            zero_actor_output: false,
            actor_output_bias: Vec::new(),
        }
    }
}

impl ModelConfig {
    /// The one rule for a network's shape and initial spread: 1 to [`MAX_LAYERS`] hidden
    /// layers, each 1 to [`MAX_WIDTH`] wide, `log_std_init` in [−20, 2], and
    /// `actor_output_bias` empty or one value in [−1, 1] per action entry. Training configs and
    /// checkpoints are both checked with it.
    pub fn check(&self) -> Result<(), String> {
        let widths_ok = self.hidden.iter().all(|w| (1..=MAX_WIDTH).contains(w));
        if self.hidden.is_empty() || self.hidden.len() > MAX_LAYERS || !widths_ok {
            return Err(format!(
                "model.hidden = {:?}: give 1 to {MAX_LAYERS} layer widths, each in 1..={MAX_WIDTH}",
                self.hidden
            ));
        }
        if !(-20.0..=2.0).contains(&self.log_std_init) {
            return Err(format!(
                "model.log_std_init = {}: must be in [-20, 2] (σ from 2e-9 to 7.4)",
                self.log_std_init
            ));
        }
        let bias = &self.actor_output_bias;
        if !bias.is_empty()
            && (bias.len() != ACT_DIM || !bias.iter().all(|b| (-1.0..=1.0).contains(b)))
        {
            return Err(format!(
                "model.actor_output_bias = {bias:?}: give none or {ACT_DIM} values (one per action entry, the gripper last), each in [-1, 1]"
            ));
        }
        Ok(())
    }
}
