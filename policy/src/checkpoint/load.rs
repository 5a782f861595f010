//! Reading a checkpoint folder: `meta.json` checked against the rules, the weights verified
//! against their checksums, and the actor they hold as a policy, without burn.

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;

use crate::actor::Actor;
use crate::agent::{ACT_DIM, GraspAgent};
use crate::burnpack::read_tensors;
use crate::checkpoint::error::{CheckpointError, err};
use crate::checkpoint::meta::{CHECKPOINT_VERSION, CheckpointMeta};
use crate::checkpoint::verify;

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
