//! `meta.json` as a type: the network's sizes and configs, the observation statistics, progress
//! and scores, and the checksums that tie it to the weights (see the [`super`] module docs).

use serde::{Deserialize, Serialize};

use crate::agent::{ACT_DIM, AgentConfig};
use crate::checkpoint::network::ModelConfig;
use crate::checkpoint::normalizer::RunningNorm;

/// The format version checkpoints are written in: 2 adds the folder checksum
/// ([`super::verify::FOLDER_CHECKSUM`]); version 1 folders still load, without it.
pub const CHECKPOINT_VERSION: u32 = 2;

/// Everything in `meta.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckpointMeta {
    /// Format version of this file.
    pub version: u32,
    pub input_dim: usize,
    pub act_dim: usize,
    pub model: ModelConfig,
    pub agent: AgentConfig,
    pub obs_norm: RunningNorm,
    /// Environment steps trained so far.
    pub timesteps: u64,
    /// PPO updates done so far.
    pub updates: u64,
    /// Training wall-clock time so far, over all invocations \[s\].
    #[serde(default)]
    pub wall_time_s: f64,
    /// Evaluation success rate of this checkpoint, if evaluated: on a task with a takt, success
    /// within it (the place task's objective).
    pub eval_success_rate: Option<f64>,
    /// The best evaluation success rate of the run up to this checkpoint (what `best` holds;
    /// within the takt on a task with one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub best_eval_success_rate: Option<f64>,
    /// The `metrics.csv` row of the update this checkpoint ends (a resume restores it if a
    /// kill came between the checkpoint and the row).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metrics_row: Option<String>,
    /// The curriculum stage the run had reached (a resume continues there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curriculum_stage: Option<usize>,
    /// `fnv1a64:` checksum of `model.bpk` with the network's shape (see the module docs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model_checksum: Option<String>,
    /// `fnv1a64:` checksum of `optimizer.bpk`, when saved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub optimizer_checksum: Option<String>,
}

/// 64-bit FNV-1a over `parts` in order, as `fnv1a64:HEX`: catches any flipped byte (not an
/// adversary; nothing here needs one).
pub fn checksum(parts: &[&[u8]]) -> String {
    let mut h = fairgrasp_types::checksum::Fnv1a64::default();
    parts.iter().for_each(|p| h.update(p));
    format!("fnv1a64:{:016x}", h.value())
}

impl CheckpointMeta {
    /// The metadata of a network that has not trained yet: this format's version, sizes from
    /// `agent`, observation statistics of nothing seen (`normalise_observations` false: never
    /// normalised), no progress, no scores and no checksums (saving adds those).
    pub fn fresh(model: ModelConfig, agent: AgentConfig, normalise_observations: bool) -> Self {
        let input_dim = agent.input_dim();
        Self {
            version: CHECKPOINT_VERSION,
            input_dim,
            act_dim: ACT_DIM,
            model,
            agent,
            obs_norm: RunningNorm::new(input_dim, normalise_observations),
            timesteps: 0,
            updates: 0,
            wall_time_s: 0.0,
            eval_success_rate: None,
            best_eval_success_rate: None,
            metrics_row: None,
            curriculum_stage: None,
            model_checksum: None,
            optimizer_checksum: None,
        }
    }

    /// What the weights must agree with: mode, action space, sizes and hidden widths.
    fn shape_key(&self) -> String {
        format!(
            "mode={:?};action_space={:?};input={};act={};hidden={:?}",
            self.agent.mode,
            self.agent.action_space,
            self.input_dim,
            self.act_dim,
            self.model.hidden
        )
    }

    /// The checksum `model_checksum` must hold for these model bytes.
    pub fn model_checksum_of(&self, model_bytes: &[u8]) -> String {
        checksum(&[self.shape_key().as_bytes(), model_bytes])
    }
}
