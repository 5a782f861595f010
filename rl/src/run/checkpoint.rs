//! Checkpoints: a folder with the network (`model.bpk`, burnpack), the optimiser state
//! (`optimizer.bpk`) and `meta.json` (sizes, configs, observation statistics, progress). What
//! reading one needs without burn (the meta, its checks, the weights' checksum) is
//! `fairgrasp_policy::checkpoint`, re-exported here; this module writes checkpoints and loads them
//! into burn to train on.
//!
//! Written atomically: into `NAME.tmp`, then `NAME` is moved to `NAME.old`, the new folder into
//! place, and `NAME.old` removed; a loader that finds no `NAME` falls back to `NAME.old`.
//!
//! Trusted only when it checks out: `meta.json` carries a checksum of `model.bpk` (and of
//! `optimizer.bpk`) taken together with the network's shape (mode, input size, hidden sizes), so
//! a flipped byte in the weights or an edited shape in the metadata is refused by name instead
//! of reaching burn. Checkpoints written before the checksum existed (the shipped ones carry it
//! now) load with the shape check of burn's loader, whose panics are caught and reported.

use std::path::Path;

use burn::module::Module;
use burn::optim::ModuleOptimizer;
use burn::tensor::Device;

use fairgrasp_policy::checkpoint::verify::{FOLDER_CHECKSUM, folder_checksum_text};
pub use fairgrasp_policy::checkpoint::{
    CHECKPOINT_VERSION, CheckpointError, CheckpointMeta, checksum, err, existing, load_meta,
    verified_model_bytes,
};

use crate::ppo::model::ActorCritic;

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
    meta.version = CHECKPOINT_VERSION;
    meta.model_checksum = Some(meta.model_checksum_of(&read("model.bpk")?));
    meta.optimizer_checksum = match optimizer {
        Some(_) => Some(checksum(&[&read("optimizer.bpk")?])),
        None => None,
    };
    let json = serde_json::to_vec_pretty(&meta).map_err(|e| err(&tmp, e))?;
    std::fs::write(tmp.join("meta.json"), &json).map_err(|e| err(&tmp, e))?;
    // One checksum over the files together: a reader never mixes two saves.
    let model_bytes = read("model.bpk")?;
    let optimizer_bytes = match optimizer {
        Some(_) => Some(read("optimizer.bpk")?),
        None => None,
    };
    let mut files: Vec<(&str, &[u8])> = vec![("meta.json", &json), ("model.bpk", &model_bytes)];
    if let Some(o) = &optimizer_bytes {
        files.push(("optimizer.bpk", o));
    }
    std::fs::write(tmp.join(FOLDER_CHECKSUM), folder_checksum_text(&files))
        .map_err(|e| err(&tmp, e))?;
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

/// Reads a checkpoint's meta and network onto `device`.
pub fn load_model(
    dir: &Path,
    device: &Device,
) -> Result<(CheckpointMeta, ActorCritic), CheckpointError> {
    let meta = load_meta(dir)?;
    // Checksum and network rule, as every loader checks them (burn's loader reads the file).
    let (path, _) = verified_model_bytes(dir, &meta)?;
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
        let bytes = fairgrasp_types::fs::read_bounded(&path, fairgrasp_types::fs::MAX_DATA_BYTES)
            .map_err(|e| err(&path, e))?;
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
