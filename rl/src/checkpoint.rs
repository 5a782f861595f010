//! Checkpoints: a folder with the network (`model.bpk`, burnpack), the optimiser state
//! (`optimizer.bpk`) and `meta.json` (sizes, configs, observation statistics, progress).
//!
//! Written atomically: into `NAME.tmp`, then `NAME` is moved to `NAME.old`, the new folder into
//! place, and `NAME.old` removed; a loader that finds no `NAME` falls back to `NAME.old`.

use std::path::{Path, PathBuf};

use burn::module::Module;
use burn::optim::ModuleOptimizer;
use burn::tensor::Device;
use serde::{Deserialize, Serialize};

use crate::agent::{ACT_DIM, AgentConfig};
use crate::model::{ActorCritic, ModelConfig};
use crate::normalizer::RunningNorm;

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
    /// Training wall-clock time so far, over all invocations [s].
    #[serde(default)]
    pub wall_time_s: f64,
    /// Evaluation success rate of this checkpoint, if evaluated.
    pub eval_success_rate: Option<f64>,
}

/// A checkpoint that cannot be read, with the file and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("checkpoint {path}: {reason}")]
pub struct CheckpointError {
    pub path: String,
    pub reason: String,
}

fn err(path: &Path, reason: impl std::fmt::Display) -> CheckpointError {
    CheckpointError {
        path: path.display().to_string(),
        reason: reason.to_string(),
    }
}

/// Writes a checkpoint folder at `dir` atomically.
pub fn save(
    dir: &Path,
    meta: &CheckpointMeta,
    model: &ActorCritic,
    optimizer: Option<&ModuleOptimizer>,
) -> Result<(), CheckpointError> {
    let tmp = dir.with_extension("tmp");
    let old = dir.with_extension("old");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).map_err(|e| err(&tmp, e))?;
    model
        .clone()
        .save_file(tmp.join("model.bpk"))
        .map_err(|e| err(&tmp, format!("writing model.bpk: {e}")))?;
    if let Some(o) = optimizer {
        o.save(tmp.join("optimizer.bpk"))
            .map_err(|e| err(&tmp, format!("writing optimizer.bpk: {e}")))?;
    }
    let json = serde_json::to_vec_pretty(meta).map_err(|e| err(&tmp, e))?;
    std::fs::write(tmp.join("meta.json"), json).map_err(|e| err(&tmp, e))?;
    let _ = std::fs::remove_dir_all(&old);
    if dir.exists() {
        std::fs::rename(dir, &old).map_err(|e| err(dir, e))?;
    }
    std::fs::rename(&tmp, dir).map_err(|e| err(dir, e))?;
    let _ = std::fs::remove_dir_all(&old);
    Ok(())
}

/// The folder to read: `dir`, or `dir.old` after an interrupted save.
fn existing(dir: &Path) -> Result<PathBuf, CheckpointError> {
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
    let text = std::fs::read_to_string(&path).map_err(|e| err(&path, e))?;
    let meta: CheckpointMeta = serde_json::from_str(&text)
        .map_err(|e| err(&path, format!("not a valid checkpoint description: {e}")))?;
    if meta.version != 1 {
        return Err(err(
            &path,
            format!(
                "format version {} is not supported (expected 1)",
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
    Ok(meta)
}

/// Reads a checkpoint's meta and network onto `device`.
pub fn load_model(
    dir: &Path,
    device: &Device,
) -> Result<(CheckpointMeta, ActorCritic), CheckpointError> {
    let meta = load_meta(dir)?;
    let dir = existing(dir)?;
    let path = dir.join("model.bpk");
    let fresh = ActorCritic::new(meta.input_dim, meta.act_dim, &meta.model, device);
    let model = fresh
        .try_load_file(&path)
        .map_err(|e| err(&path, format!("cannot load the network: {e}")))?;
    Ok((meta, model))
}

/// Reads the optimiser state saved beside a model, if present.
pub fn load_optimizer(
    dir: &Path,
    optimizer: ModuleOptimizer,
) -> Result<ModuleOptimizer, CheckpointError> {
    let dir = existing(dir)?;
    let path = dir.join("optimizer.bpk");
    if !path.exists() {
        return Ok(optimizer);
    }
    optimizer
        .load(&path)
        .map_err(|e| err(&path, format!("cannot load the optimiser state: {e}")))
}
