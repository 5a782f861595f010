//! What makes a checkpoint trusted beyond its weights' checksum: every number of `meta.json`
//! within the range training can produce, and one checksum over the folder's files together
//! (`checksum`: `meta.json`, `model.bpk`, `optimizer.bpk`), so an edited `meta.json` or files of
//! two different saves are refused by name instead of loading into a policy that scores 0 %.

use std::path::Path;

use crate::checkpoint::error::{CheckpointError, err};
use crate::checkpoint::meta::{CheckpointMeta, checksum};

/// The longest run in environment steps (10¹⁰: years on a laptop); also caps the counters of a
/// checkpoint (an update holds at least one step).
pub const MAX_TIMESTEPS: u64 = 10_000_000_000;

/// The largest observation statistic a checkpoint may hold (observations are metres, radians,
/// their rates and flags: far below this).
const MAX_OBS_STAT: f64 = 1e6;

/// The highest curriculum stage a checkpoint may record.
const MAX_STAGE: usize = 64;

/// The name of the folder checksum file.
pub const FOLDER_CHECKSUM: &str = "checksum";

/// The first format version whose folders must carry [`FOLDER_CHECKSUM`].
pub const FOLDER_CHECKSUM_VERSION: u32 = 2;

/// The files the folder checksum covers, in order (`optimizer.bpk` only when present).
pub const CHECKED_FILES: [&str; 3] = ["meta.json", "model.bpk", "optimizer.bpk"];

/// A number as a message quotes it: exponent form when it is very large or small.
fn short(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Checks every number of `meta` against the range training produces; the message names the
/// field, its value and the range.
pub fn check_numbers(meta: &CheckpointMeta) -> Result<(), String> {
    let norm = &meta.obs_norm;
    let bad_stat = |values: &[f64], low: f64| {
        values
            .iter()
            .position(|v| !(v.is_finite() && *v >= low && v.abs() <= MAX_OBS_STAT))
    };
    if let Some(i) = bad_stat(&norm.mean, -MAX_OBS_STAT) {
        return Err(format!(
            "obs_norm.mean[{i}] = {}: must be a finite number within ±{MAX_OBS_STAT:e}",
            short(norm.mean[i])
        ));
    }
    if let Some(i) = bad_stat(&norm.var, 0.0) {
        return Err(format!(
            "obs_norm.var[{i}] = {}: must be finite and in [0, {MAX_OBS_STAT:e}]",
            short(norm.var[i])
        ));
    }
    if !(norm.count.is_finite() && norm.count > 0.0 && norm.count <= 1e12) {
        return Err(format!(
            "obs_norm.count = {}: must be in (0, 1e12] observations",
            short(norm.count)
        ));
    }
    meta.agent.check()?;
    if meta.timesteps > MAX_TIMESTEPS {
        return Err(format!(
            "timesteps = {}: must be at most {MAX_TIMESTEPS}",
            meta.timesteps
        ));
    }
    if meta.updates > meta.timesteps {
        return Err(format!(
            "updates = {}: must be at most timesteps ({}; every update takes steps)",
            meta.updates, meta.timesteps
        ));
    }
    if !(meta.wall_time_s.is_finite() && (0.0..=1e9).contains(&meta.wall_time_s)) {
        return Err(format!(
            "wall_time_s = {}: must be in [0, 1e9] seconds",
            short(meta.wall_time_s)
        ));
    }
    for (field, rate) in [
        ("eval_success_rate", meta.eval_success_rate),
        ("best_eval_success_rate", meta.best_eval_success_rate),
    ] {
        if let Some(r) = rate
            && !(0.0..=1.0).contains(&r)
        {
            return Err(format!("{field} = {}: must be in [0, 1]", short(r)));
        }
    }
    if let Some(stage) = meta.curriculum_stage
        && stage > MAX_STAGE
    {
        return Err(format!(
            "curriculum_stage = {stage}: must be at most {MAX_STAGE}"
        ));
    }
    Ok(())
}

/// The text of a folder checksum file over `files` (name, bytes), in order.
pub fn folder_checksum_text(files: &[(&str, &[u8])]) -> String {
    let mut parts: Vec<Vec<u8>> = Vec::new();
    for (name, bytes) in files {
        parts.push(format!("{name}\0{}\0", bytes.len()).into_bytes());
        parts.push(bytes.to_vec());
    }
    let refs: Vec<&[u8]> = parts.iter().map(Vec::as_slice).collect();
    let names: Vec<&str> = files.iter().map(|(n, _)| *n).collect();
    format!("{} {}\n", checksum(&refs), names.join(" "))
}

/// The bytes of a checkpoint's `meta.json` and `model.bpk`, checked together.
pub struct CheckedFiles {
    pub meta: Vec<u8>,
    pub model: Vec<u8>,
}

/// Reads the folder's checksum file and checks it against the files it names; `required`
/// (a format version that writes one) refuses a folder without it. Returns the checked bytes
/// (None without a checksum file).
pub fn verify_folder(dir: &Path, required: bool) -> Result<Option<CheckedFiles>, CheckpointError> {
    let path = dir.join(FOLDER_CHECKSUM);
    let text = match fairgrasp_types::fs::read_text_bounded(&path, 4096) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && !required => return Ok(None),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(err(
                &path,
                "missing: this checkpoint's format writes one over meta.json and the weights; without it the files cannot be trusted together",
            ));
        }
        Err(e) => return Err(err(&path, e)),
    };
    let mut words = text.split_whitespace();
    let expected = words.next().unwrap_or_default().to_string();
    let names: Vec<&str> = words.collect();
    let known = |n: &&str| CHECKED_FILES.contains(n);
    if names.len() < 2 || names[..2] != CHECKED_FILES[..2] || !names.iter().all(known) {
        return Err(err(
            &path,
            "not a checksum file fairgrasp writes (it must name meta.json, model.bpk and optionally optimizer.bpk)",
        ));
    }
    let mut files = Vec::new();
    for name in &names {
        let file = dir.join(name);
        let bytes = fairgrasp_types::fs::read_bounded(&file, fairgrasp_types::fs::MAX_DATA_BYTES)
            .map_err(|e| err(&file, e))?;
        files.push((*name, bytes));
    }
    let refs: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    let found = folder_checksum_text(&refs);
    if found.split_whitespace().next() != Some(expected.as_str()) {
        return Err(err(
            dir,
            format!(
                "the files differ from their checksum ({expected} in {FOLDER_CHECKSUM}): one of {} was changed after it was saved, or they come from two different saves",
                names.join(", ")
            ),
        ));
    }
    let mut files = files.into_iter().map(|(_, b)| b);
    match (files.next(), files.next()) {
        (Some(meta), Some(model)) => Ok(Some(CheckedFiles { meta, model })),
        _ => Ok(None),
    }
}
