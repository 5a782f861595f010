//! Checkpoints: a folder with the network (`model.bpk`, burnpack), the optimiser state
//! (`optimizer.bpk`) and `meta.json` (sizes, configs, observation statistics, progress).
//!
//! Written atomically: into `NAME.tmp`, then `NAME` is moved to `NAME.old`, the new folder into
//! place, and `NAME.old` removed; a loader that finds no `NAME` falls back to `NAME.old`.
//!
//! Trusted only when it checks out: `meta.json` carries a checksum of `model.bpk` (and of
//! `optimizer.bpk`) taken together with the network's shape (mode, input size, hidden sizes), so
//! a flipped byte in the weights or an edited shape in the metadata is refused by name instead
//! of reaching burn. Checkpoints written before the checksum existed (the shipped ones carry it
//! now) load with the shape check of burn's loader, whose panics are caught and reported.

use std::path::{Path, PathBuf};

use burn::module::Module;
use burn::optim::ModuleOptimizer;
use burn::tensor::Device;
use serde::{Deserialize, Serialize};

use crate::agent::grasp_agent::{ACT_DIM, AgentConfig};
use crate::ppo::model::{ActorCritic, ModelConfig};
use crate::ppo::normalizer::RunningNorm;

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
    let read = |name: &str| std::fs::read(tmp.join(name)).map_err(|e| err(&tmp.join(name), e));
    let mut meta = meta.clone();
    meta.model_checksum = Some(meta.model_checksum_of(&read("model.bpk")?));
    meta.optimizer_checksum = match optimizer {
        Some(_) => Some(checksum(&[&read("optimizer.bpk")?])),
        None => None,
    };
    let json = serde_json::to_vec_pretty(&meta).map_err(|e| err(&tmp, e))?;
    std::fs::write(tmp.join("meta.json"), json).map_err(|e| err(&tmp, e))?;
    sync_dir_files(&tmp);
    let name = dir
        .file_name()
        .map_or(String::new(), |n| n.to_string_lossy().into_owned());
    crate::run::crash::point(&format!("{name}:checkpoint_written"), meta.updates);
    // `old` may be the only good copy (a kill came after the last save moved `dir` aside): it
    // is replaced only when `dir` exists to take its place.
    if dir.exists() {
        let _ = std::fs::remove_dir_all(&old);
        std::fs::rename(dir, &old).map_err(|e| err(dir, e))?;
    }
    crate::run::crash::point(&format!("{name}:checkpoint_moved_aside"), meta.updates);
    std::fs::rename(&tmp, dir).map_err(|e| err(dir, e))?;
    let _ = std::fs::remove_dir_all(&old);
    Ok(())
}

/// Flushes the files of a freshly written folder to disk before it is renamed into place (a
/// power cut must not leave a renamed folder of empty files); best effort.
fn sync_dir_files(dir: &Path) {
    if let Ok(entries) = std::fs::read_dir(dir) {
        for entry in entries.flatten() {
            if let Ok(f) = std::fs::File::open(entry.path()) {
                let _ = f.sync_all();
            }
        }
    }
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
    let bytes = std::fs::read(&path).map_err(|e| err(&path, e))?;
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
    // The fresh weights are replaced by the file's: any seed will do.
    let fresh = ActorCritic::new(meta.input_dim, meta.act_dim, &meta.model, 0, device);
    // burn's loader panics on some shape mismatches; report them as this checkpoint's error.
    let loaded =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| fresh.try_load_file(&path)));
    let model = match loaded {
        Ok(result) => result.map_err(|e| err(&path, format!("cannot load the network: {e}")))?,
        Err(_) => {
            return Err(err(
                &path,
                format!(
                    "the weights do not fit meta.json's network (input {}, hidden {:?}, {} actions)",
                    meta.input_dim, meta.model.hidden, meta.act_dim
                ),
            ));
        }
    };
    Ok((meta, model))
}

/// Reads the optimiser state saved beside a model, if present.
pub fn load_optimizer(
    dir: &Path,
    optimizer: ModuleOptimizer,
) -> Result<ModuleOptimizer, CheckpointError> {
    let meta = load_meta(dir)?;
    let dir = existing(dir)?;
    let path = dir.join("optimizer.bpk");
    if !path.exists() {
        return Ok(optimizer);
    }
    if let Some(expected) = &meta.optimizer_checksum {
        let bytes = std::fs::read(&path).map_err(|e| err(&path, e))?;
        let found = checksum(&[&bytes]);
        if &found != expected {
            return Err(err(
                &path,
                format!(
                    "checksum {found} differs from meta.json's {expected}: the optimiser state is corrupted"
                ),
            ));
        }
    }
    optimizer
        .load(&path)
        .map_err(|e| err(&path, format!("cannot load the optimiser state: {e}")))
}
