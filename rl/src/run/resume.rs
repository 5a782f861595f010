//! Continuing a run folder safely (which folders a fresh run or a resume accepts is
//! [`crate::run::folder`]): the config a resume may change, `metrics.csv` repaired to match `checkpoints/latest`, and the best score
//! carried over.
//!
//! The invariant a kill at any point keeps: `metrics.csv` holds exactly one row per update up to
//! the one `checkpoints/latest` ends, because the row is saved inside the checkpoint first and
//! appended to `metrics.csv` second; a resume drops rows past the checkpoint and restores a row
//! the kill cut off.

use std::path::Path;

use fairgrasp_policy::recipe::read;
use fairgrasp_types::write_atomic;

use crate::run::checkpoint::{self, CheckpointMeta};
use crate::run::config::TrainConfig;
use crate::run::error::{TrainError, io};
use crate::run::inputs::{self, InputsRecord};
use crate::run::snapshot::{ENV_SNAPSHOT, env_snapshot_of};

/// Fields a resume may change without `--accept-config-changes`: how long to run and on how many
/// threads (results do not depend on the thread count).
const FREELY_CHANGED: [&str; 3] = ["total_timesteps", "max_wall_time_s", "threads"];

/// Fields no resume can change: the saved network has their shape (`model.hidden`, and the
/// input size through `agent.mode`/`agent.action_space`), and the checkpoint's `[agent]` is what
/// every evaluation of it uses.
const FIXED_FIELDS: [&str; 2] = ["model.hidden", "agent"];

/// How `train` treats an existing run folder.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ResumeOptions {
    /// Continue from `checkpoints/latest` (`--resume`).
    pub resume: bool,
    /// Accept a config that differs from the run's `config.toml` (recorded in
    /// `config_changes.log`, and `config.toml` rewritten).
    pub accept_config_changes: bool,
    /// Without `resume`: move a run the folder holds aside and start over (`--force`).
    pub force: bool,
}

/// The config the run in `run_dir` trains with, held to what it started with: the preset file
/// from the run's copy ([`training_config`]), the config checked against the run's
/// `config.toml` and what the recipe names against the run's record of it
/// ([`crate::run::inputs`]) when resuming. Writes (`config.toml` on a resume, `env.toml`,
/// `inputs.toml`) only once every check has passed: a refused resume changes nothing.
pub fn config_for_run(
    config: &TrainConfig,
    run_dir: &Path,
    resume: bool,
    accept_changes: bool,
) -> Result<TrainConfig, TrainError> {
    let config = training_config(config, run_dir, resume)?;
    let now = InputsRecord::now(&config)?;
    if resume {
        let changed = inputs::changes_since_start(run_dir, &now)?;
        check_config(run_dir, &config, &changed, accept_changes)?;
    }
    save_env_snapshot(&config, run_dir)?;
    now.save(run_dir)?;
    Ok(config)
}

/// The config a run trains with. A run started from a preset file (`preset = "….toml"`) keeps
/// a copy of it as `RUN/env.toml` ([`save_env_snapshot`]), and a resume trains on that copy,
/// from whatever folder it is started (a relative `preset` would otherwise name another file
/// there); a preset file there that differs from the copy is not used, and a note names the
/// first field that differs. A resume whose recipe names another preset than the run's
/// `config.toml` (a change [`check_config`] refuses unless accepted) trains on the file named.
/// Writes nothing.
pub fn training_config(
    config: &TrainConfig,
    run_dir: &Path,
    resume: bool,
) -> Result<TrainConfig, TrainError> {
    let mut config = config.clone();
    config.env_snapshot = None;
    let same_preset = || saved_config(run_dir).is_ok_and(|saved| saved.preset == config.preset);
    if resume
        && let Some(kept) = env_snapshot_of(&config.preset, run_dir)
        && same_preset()
    {
        if let Some(difference) = file_difference(&kept, Path::new(&config.preset)) {
            eprintln!(
                "note: the run trains on its own copy of its preset ({}, saved when it started); {} here {difference} and is not used",
                kept.display(),
                config.preset
            );
        }
        config.env_snapshot = Some(kept);
    }
    config.validate().map_err(TrainError::Config)?;
    Ok(config)
}

/// How the preset file `here` differs from the run's copy `kept`: `None` if it reads the same,
/// else `is missing` or `differs (field: copy → here)`.
fn file_difference(kept: &Path, here: &Path) -> Option<String> {
    let read =
        |p: &Path| fairgrasp_types::fs::read_bounded(p, fairgrasp_types::fs::MAX_CONFIG_BYTES);
    let (Ok(copy), Ok(file)) = (read(kept), read(here)) else {
        return Some("is missing or unreadable".into());
    };
    if copy == file {
        return None;
    }
    let env = |p: &Path| {
        fairgrasp_env::config::presets::load(&p.to_string_lossy())
            .ok()
            .and_then(|e| toml::Table::try_from(&e).ok())
    };
    let field = match (env(kept), env(here)) {
        (Some(a), Some(b)) => crate::run::inputs::first_difference(&a, &b)
            .unwrap_or_else(|| "only in its text: the same env".into()),
        _ => "it is not a valid env file".into(),
    };
    Some(format!("differs ({field})"))
}

/// Keeps the run's copy of the preset file `config` trains on (`RUN/env.toml`), unless it
/// already trains on that copy: at a fresh start, and when a resume accepted another preset.
pub fn save_env_snapshot(config: &TrainConfig, run_dir: &Path) -> Result<(), TrainError> {
    if !config.preset.ends_with(".toml") || config.env_snapshot.is_some() {
        return Ok(());
    }
    let preset = Path::new(&config.preset);
    let bytes = fairgrasp_types::fs::read_bounded(preset, fairgrasp_types::fs::MAX_CONFIG_BYTES)
        .map_err(io(preset))?;
    let snapshot = run_dir.join(ENV_SNAPSHOT);
    write_atomic(&snapshot, &bytes).map_err(io(&snapshot))
}

/// The run's own config (`RUN/config.toml`), as saved.
fn saved_config(run_dir: &Path) -> Result<TrainConfig, TrainError> {
    let path = run_dir.join("config.toml");
    let text = fairgrasp_types::fs::read_text_bounded(&path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
        .map_err(io(&path))?;
    toml::from_str(&text).map_err(|e| TrainError::Config(format!("{}: {e}", path.display())))
}

/// The seed a resume trains with when none is given again: the one the run in `run_dir` was
/// started with (its `config.toml`), else `given` (a folder with no run yet).
pub fn run_seed(run_dir: &Path, given: u64) -> Result<u64, TrainError> {
    let saved = run_dir.join("config.toml");
    // Only a run's own config.toml (a folder that holds no run is refused by the trainer).
    if crate::run::folder::inspect(run_dir) == crate::run::folder::FolderState::Run {
        Ok(TrainConfig::from_toml_file_in(&saved, Some(run_dir))?.seed)
    } else {
        Ok(given)
    }
}

/// The differences between the run's saved config and the new one, as `field: old → new`
/// (fields in `FREELY_CHANGED` left out).
pub fn config_differences(
    saved: &TrainConfig,
    new: &TrainConfig,
) -> Result<Vec<String>, TrainError> {
    let value = |c: &TrainConfig| {
        toml::Value::try_from(c).map_err(|e| TrainError::Config(format!("comparing configs: {e}")))
    };
    Ok(read::leaf_differences(&value(saved)?, &value(new)?)
        .into_iter()
        .filter(|c| !FREELY_CHANGED.contains(&c.path.as_str()))
        .map(|c| c.to_string())
        .collect())
}

/// Checks a resume against the run: its config against the run's `config.toml`, and
/// `inputs_changed`, what the recipe names that reads differently than when the run started
/// ([`crate::run::inputs`]). Refuses differences unless accepted, never accepts a change of the
/// network's shape, and records accepted ones in `config_changes.log`; `config.toml` is
/// rewritten to say what runs now.
pub fn check_config(
    run_dir: &Path,
    config: &TrainConfig,
    inputs_changed: &[String],
    accept: bool,
) -> Result<(), TrainError> {
    let path = run_dir.join("config.toml");
    let diffs = config_differences(&saved_config(run_dir)?, config)?;
    let write_config = || {
        let toml = toml::to_string_pretty(config)
            .map_err(|e| TrainError::Config(format!("config.toml: {e}")))?;
        write_atomic(&path, toml.as_bytes()).map_err(io(&path))
    };
    if diffs.is_empty() && inputs_changed.is_empty() {
        // Only the freely changed fields (if any) differ: config.toml says what runs now.
        return write_config();
    }
    let shape: Vec<&str> = diffs
        .iter()
        .filter(|d| FIXED_FIELDS.iter().any(|f| d.starts_with(f)))
        .map(String::as_str)
        .collect();
    if !shape.is_empty() {
        return Err(TrainError::Config(format!(
            "cannot resume {} with a different network shape or [agent] ({}): the checkpoint's weights and agent are the old ones; start a new run folder instead",
            run_dir.display(),
            shape.join("; ")
        )));
    }
    let mut what = Vec::new();
    if !diffs.is_empty() {
        what.push(format!(
            "the config differs from the run's config.toml ({})",
            diffs.join("; ")
        ));
    }
    if !inputs_changed.is_empty() {
        what.push(format!(
            "what the recipe names is not what the run started with ({})",
            inputs_changed.join("; ")
        ));
    }
    if !accept {
        return Err(TrainError::Config(format!(
            "{}; pass --accept-config-changes to continue with the new values (recorded in config_changes.log), or resume with the old config from the folder the run was started in",
            what.join(", and ")
        )));
    }
    let list = diffs
        .iter()
        .chain(inputs_changed)
        .map(String::as_str)
        .collect::<Vec<_>>()
        .join("; ");
    let log = run_dir.join("config_changes.log");
    let mut previous = std::fs::read_to_string(&log).unwrap_or_default();
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    previous.push_str(&format!("unix time {stamp}: {list}\n"));
    write_atomic(&log, previous.as_bytes()).map_err(io(&log))?;
    write_config()
}

/// The best evaluation score the run has reached: from `latest`'s record and from
/// `checkpoints/best` itself (older checkpoints record only their own score). −1: none yet.
pub fn best_so_far(run_dir: &Path, latest: &CheckpointMeta) -> f64 {
    let best_dir = run_dir.join("checkpoints/best");
    let from_best = checkpoint::load_meta(&best_dir)
        .ok()
        .and_then(|m| m.eval_success_rate);
    [latest.best_eval_success_rate, from_best]
        .into_iter()
        .flatten()
        .fold(-1.0, f64::max)
}

/// Rewrites `metrics.csv` to hold one row per update up to `meta.updates`, in order, and
/// restores the checkpoint's own row if it is missing (a kill between the checkpoint and the
/// row). History is never shortened: a line that cannot be a row here (torn by a kill, not
/// UTF-8, past the checkpoint, out of order) is appended to `metrics.rejected.csv` before
/// `metrics.csv` is rewritten. Rows missing further back (a file from before rows travelled in
/// checkpoints, or a power cut before the append reached the disk) cannot be restored: they are
/// counted in the result. A file written before columns were added at the end of the header
/// (the outcome shares) keeps its rows, padded with empty cells. Returns (lines set aside, rows
/// restored, updates still without a row).
pub fn repair_metrics(
    run_dir: &Path,
    meta: &CheckpointMeta,
    header: &str,
) -> Result<(usize, usize, u64), TrainError> {
    let path = run_dir.join("metrics.csv");
    let bytes = match fairgrasp_types::fs::read_bounded(&path, fairgrasp_types::fs::MAX_DATA_BYTES)
    {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(e) => return Err(io(&path)(e)),
    };
    let older_header = |l: &str| l != header && header.starts_with(&format!("{l},"));
    let mut rows: Vec<&str> = Vec::new();
    let mut aside: Vec<&[u8]> = Vec::new();
    let mut last = 0u64;
    let mut lines: Vec<&[u8]> = bytes.split(|b| *b == b'\n').collect();
    // The piece after the last newline: empty for a complete file, else a line a kill tore.
    if let Some(torn) = lines.pop().filter(|t| !t.is_empty()) {
        aside.push(torn);
    }
    for raw in lines {
        let Ok(line) = std::str::from_utf8(raw) else {
            aside.push(raw);
            continue;
        };
        if line.is_empty() || line == header || older_header(line) {
            continue;
        }
        match line.split(',').next().and_then(|u| u.parse::<u64>().ok()) {
            Some(u) if u > last && u <= meta.updates => {
                rows.push(line);
                last = u;
            }
            _ => aside.push(raw),
        }
    }
    let mut restored = 0;
    if last < meta.updates
        && let Some(row) = &meta.metrics_row
    {
        rows.push(row);
        restored = 1;
    }
    let missing = meta.updates.saturating_sub(rows.len() as u64);
    if !aside.is_empty() {
        let rejected = run_dir.join("metrics.rejected.csv");
        let mut kept = match std::fs::read(&rejected) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
            Err(e) => return Err(io(&rejected)(e)),
        };
        for line in &aside {
            kept.extend_from_slice(line);
            kept.push(b'\n');
        }
        write_atomic(&rejected, &kept).map_err(io(&rejected))?;
    }
    if !aside.is_empty() || restored > 0 || !bytes.starts_with(header.as_bytes()) {
        let mut out = format!("{header}\n");
        let columns = header.split(',').count();
        for row in &rows {
            out.push_str(row);
            for _ in row.split(',').count()..columns {
                out.push(',');
            }
            out.push('\n');
        }
        write_atomic(&path, out.as_bytes()).map_err(io(&path))?;
    }
    Ok((aside.len(), restored, missing))
}
