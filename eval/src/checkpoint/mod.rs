//! Checkpoints as they are read after training: `meta.json` (sizes, configs, observation
//! statistics, progress) checked against the rules, and the weights of `model.bpk` verified
//! against its checksum and run as a plain-array [`Actor`], without burn. Writing checkpoints
//! (and loading them into burn to train on) is `fairgrasp-rl`'s `run::checkpoint`.
//!
//! A checkpoint folder holds the network (`model.bpk`, burnpack), the optimiser state
//! (`optimizer.bpk`) and `meta.json`. A loader that finds no `meta.json` in `NAME` falls back to
//! `NAME.old` (a save interrupted between its two renames).
//!
//! Trusted only when it checks out: `meta.json` carries a checksum of `model.bpk` (and of
//! `optimizer.bpk`) taken together with the network's shape (mode, input size, hidden sizes), so
//! a flipped byte in the weights or an edited shape in the metadata is refused by name.
//!
//! - [`network`]: the network's shape and its rule; [`normalizer`]: the observation statistics;
//!   [`verify`]: the ranges of `meta.json`'s numbers and the checksum over the folder's files.

pub mod network;
pub mod normalizer;
pub mod verify;

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use serde::{Deserialize, Serialize};

use crate::actor::Actor;
use crate::agent::{ACT_DIM, AgentConfig, GraspAgent};
use crate::burnpack::read_tensors;
use network::ModelConfig;
use normalizer::RunningNorm;

/// The format version checkpoints are written in: 2 adds the folder checksum
/// ([`verify::FOLDER_CHECKSUM`]); version 1 folders still load, without it.
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
    /// Evaluation success rate of this checkpoint, if evaluated.
    pub eval_success_rate: Option<f64>,
    /// The best evaluation success rate of the run up to this checkpoint (what `best` holds).
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

/// A checkpoint that cannot be read, with the file and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("checkpoint {path}: {reason}")]
pub struct CheckpointError {
    pub path: String,
    pub reason: String,
}

/// A [`CheckpointError`] for `path`.
pub fn err(path: &Path, reason: impl std::fmt::Display) -> CheckpointError {
    CheckpointError {
        path: path.display().to_string(),
        reason: reason.to_string(),
    }
}

/// The folder to read: `dir`, or `dir.old` after an interrupted save.
pub fn existing(dir: &Path) -> Result<PathBuf, CheckpointError> {
    if dir.join("meta.json").exists() {
        return Ok(dir.to_path_buf());
    }
    let old = dir.with_extension("old");
    if old.join("meta.json").exists() {
        return Ok(old);
    }
    Err(err(
        dir,
        "no meta.json here (is this a checkpoint folder written by `fairgrasp train`?)",
    ))
}

/// Reads `meta.json`.
pub fn load_meta(dir: &Path) -> Result<CheckpointMeta, CheckpointError> {
    let dir = existing(dir)?;
    let path = dir.join("meta.json");
    let text = fairgrasp_types::fs::read_text_bounded(&path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
        .map_err(|e| err(&path, e))?;
    let meta: CheckpointMeta = serde_json::from_str(&text)
        .map_err(|e| err(&path, format!("not a valid checkpoint description: {e}")))?;
    if !(1..=CHECKPOINT_VERSION).contains(&meta.version) {
        return Err(err(
            &path,
            format!(
                "format version {} is not supported (1 to {CHECKPOINT_VERSION})",
                meta.version
            ),
        ));
    }
    if meta.act_dim != ACT_DIM || meta.input_dim != meta.agent.input_dim() {
        return Err(err(
            &path,
            format!(
                "input_dim {} and act_dim {} do not fit a {} agent (input {}, {ACT_DIM} actions)",
                meta.input_dim,
                meta.act_dim,
                meta.agent.mode,
                meta.agent.input_dim()
            ),
        ));
    }
    if meta.obs_norm.mean.len() != meta.input_dim || meta.obs_norm.var.len() != meta.input_dim {
        return Err(err(
            &path,
            "the observation statistics do not match input_dim",
        ));
    }
    verify::check_numbers(&meta).map_err(|e| err(&path, e))?;
    Ok(meta)
}

/// Reads `model.bpk` of the checkpoint `dir` (or `dir.old`) and checks it against `meta`'s
/// checksum and network rule: the bytes every loader of the weights starts from.
pub fn verified_model_bytes(
    dir: &Path,
    meta: &CheckpointMeta,
) -> Result<(PathBuf, Vec<u8>), CheckpointError> {
    let dir = existing(dir)?;
    let path = dir.join("model.bpk");
    let required = meta.version >= verify::FOLDER_CHECKSUM_VERSION;
    let bytes = match verify::verify_folder(&dir, required)? {
        Some(checked_files) => {
            // The meta given must be the one the checksum covers (not one of another save).
            let checked: Option<CheckpointMeta> = serde_json::from_slice(&checked_files.meta).ok();
            if checked.as_ref() != Some(meta) {
                return Err(err(
                    &dir.join("meta.json"),
                    "changed while it was being read (a save in progress?): read it again",
                ));
            }
            checked_files.model
        }
        None => fairgrasp_types::fs::read_bounded(&path, fairgrasp_types::fs::MAX_DATA_BYTES)
            .map_err(|e| err(&path, e))?,
    };
    if let Some(expected) = &meta.model_checksum {
        let found = meta.model_checksum_of(&bytes);
        if &found != expected {
            return Err(err(
                &path,
                format!(
                    "checksum {found} differs from meta.json's {expected}: the weights are corrupted, or meta.json was edited (mode, input_dim or model.hidden no longer match the weights)"
                ),
            ));
        }
    }
    if let Err(reason) = meta.model.check() {
        return Err(err(
            &dir.join("meta.json"),
            format!("{reason}: not a network this tool writes"),
        ));
    }
    Ok((path, bytes))
}

/// Reads a checkpoint's meta and its actor (the mean action), without burn.
pub fn load_actor(dir: &Path) -> Result<(CheckpointMeta, Actor), CheckpointError> {
    let meta = load_meta(dir)?;
    let (path, bytes) = verified_model_bytes(dir, &meta)?;
    let tensors = read_tensors(&bytes).map_err(|e| err(&path, e))?;
    let mut sizes = vec![meta.input_dim];
    sizes.extend(&meta.model.hidden);
    sizes.push(meta.act_dim);
    let actor = Actor::from_tensors(&tensors, &sizes).map_err(|e| {
        err(
            &path,
            format!("the weights do not fit meta.json's network: {e}"),
        )
    })?;
    Ok((meta, actor))
}

/// A trained agent as a policy for `env`: its deterministic (mean) action, computed by the
/// burn-free [`Actor`] on observations normalised with the checkpoint's statistics.
pub fn actor_policy(meta: &CheckpointMeta, actor: &Actor, env: &EnvConfig) -> GraspAgent {
    let (actor, norm) = (actor.clone(), meta.obs_norm.clone());
    let mean = move |x: &[f32]| actor.mean(&norm.normalize(x));
    GraspAgent::new(meta.agent.clone(), env, Box::new(mean))
}
