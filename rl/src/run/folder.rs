//! What a run folder holds, and who may train in it.
//!
//! A run folder is identified by what it holds ([`inspect`]): nothing yet, a run killed before
//! its first checkpoint, a run with `checkpoints/latest`, a run whose history survives but whose
//! `checkpoints/latest` is missing or damaged, or a folder that is not a run's at all. [`decide`]
//! turns that and the user's flags into a fresh start or a resume, and refuses every case in which
//! starting would overwrite history; `--force` moves the old run aside ([`move_aside`]), it never
//! deletes it. [`RunLock`] keeps a second process out of a folder while one trains in it.

use std::path::{Path, PathBuf};

use fairgrasp_types::fs::{FolderLock, LockRefused};

use crate::run::checkpoint;
use crate::run::error::{TrainError, io};
use crate::run::inputs::INPUTS_RECORD;
use crate::run::snapshot::ENV_SNAPSHOT;

/// The lock file inside a run folder (holds the training process's pid while it runs).
pub const LOCK_FILE: &str = ".lock";

/// The names a run writes at the top of its folder (anything else is the user's).
const RUN_FILES: [&str; 9] = [
    "config.toml",
    "metrics.csv",
    "checkpoints",
    "eval.json",
    ENV_SNAPSHOT,
    INPUTS_RECORD,
    "config_changes.log",
    "metrics.rejected.csv",
    LOCK_FILE,
];

/// What a folder holds, as far as training is concerned.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FolderState {
    /// Missing, or empty (a lock file aside).
    Empty,
    /// A run killed before its first checkpoint: `config.toml`, at most `metrics.csv`'s header,
    /// no checkpoint, no evaluation. Nothing in it is worth keeping.
    Unstarted,
    /// A run with a loadable `checkpoints/latest` (or `latest.old`, a kill between two saves).
    Run,
    /// A run whose history exists but cannot be continued; the text says what is missing.
    Damaged(String),
    /// A folder that holds no run (no `config.toml`); the names it holds.
    Foreign(Vec<String>),
}

/// Data rows of `metrics.csv` (lines after the header that are not empty), 0 if unreadable.
fn metrics_rows(run_dir: &Path) -> usize {
    let Ok(bytes) = fairgrasp_types::fs::read_bounded(
        &run_dir.join("metrics.csv"),
        fairgrasp_types::fs::MAX_DATA_BYTES,
    ) else {
        return 0;
    };
    bytes
        .split(|b| *b == b'\n')
        .skip(1)
        .filter(|l| !l.iter().all(u8::is_ascii_whitespace))
        .count()
}

/// Classifies `run_dir` (see [`FolderState`]).
pub fn inspect(run_dir: &Path) -> FolderState {
    let Ok(entries) = std::fs::read_dir(run_dir) else {
        return FolderState::Empty;
    };
    let mut names: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != LOCK_FILE)
        .collect();
    names.sort();
    // A fresh start that stopped after copying its preset file or recording its inputs, and
    // before config.toml.
    if names
        .iter()
        .all(|n| n == ENV_SNAPSHOT || n == INPUTS_RECORD)
    {
        return FolderState::Empty;
    }
    if !run_dir.join("config.toml").is_file() {
        return FolderState::Foreign(names);
    }
    let checkpoints = run_dir.join("checkpoints");
    let config_is_run = fairgrasp_types::fs::read_text_bounded(
        &run_dir.join("config.toml"),
        fairgrasp_types::fs::MAX_CONFIG_BYTES,
    )
    .is_ok_and(|t| toml::from_str::<crate::run::TrainConfig>(&t).is_ok());
    if !config_is_run {
        return if checkpoints.is_dir() {
            FolderState::Damaged("a config.toml that is not a training config".into())
        } else {
            FolderState::Foreign(names)
        };
    }
    let latest = checkpoints.join("latest");
    let latest_old = checkpoints.join("latest.old");
    let loadable = [&latest, &latest_old]
        .iter()
        .any(|d| d.is_dir() && checkpoint::load_meta(d).is_ok());
    if loadable {
        return FolderState::Run;
    }
    let mut history = Vec::new();
    if latest.exists() || latest_old.exists() {
        history.push("a checkpoints/latest that cannot be read (no valid meta.json)".to_string());
    }
    let rows = metrics_rows(run_dir);
    if rows > 0 {
        history.push(format!("{rows} rows of metrics.csv"));
    }
    for kept in ["checkpoints/best", "eval.json"] {
        if run_dir.join(kept).exists() {
            history.push(kept.to_string());
        }
    }
    if !history.is_empty() {
        return FolderState::Damaged(history.join(", "));
    }
    // Nothing to keep, but a fresh start rewrites config.toml and metrics.csv: only if both are
    // a run's (every name is one a run writes).
    if names.iter().any(|n| !is_run_name(n)) {
        FolderState::Foreign(names)
    } else {
        FolderState::Unstarted
    }
}

/// Whether a run writes this name at the top of its folder.
fn is_run_name(name: &str) -> bool {
    RUN_FILES.contains(&name) || name.starts_with("events.out.tfevents.")
}

/// How a run was asked to start.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StartFlags {
    /// `--resume`: continue from `checkpoints/latest`.
    pub resume: bool,
    /// `--force`: move whatever run the folder holds aside ([`move_aside`]) and start over.
    pub force: bool,
}

/// What `train` does with the folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Start {
    /// Start a new run (the folder is empty or holds nothing worth keeping).
    Fresh,
    /// Continue the run from `checkpoints/latest`.
    Resume,
    /// Move the old run to the path given, then start a new one.
    FreshAfterMovingAside(PathBuf),
}

/// Decides between a fresh start and a resume, refusing every case that would lose history.
pub fn decide(run_dir: &Path, flags: StartFlags) -> Result<Start, TrainError> {
    let shown = run_dir.display();
    let refuse = |m: String| Err(TrainError::Config(m));
    match inspect(run_dir) {
        FolderState::Foreign(names) => refuse(format!(
            "{shown} is not a run folder (it holds {} and no config.toml): nothing is written into it, even with --force; choose another --run-dir",
            excerpt(&names)
        )),
        FolderState::Empty if flags.resume => refuse(format!(
            "--resume: {shown} holds no run (no config.toml, no checkpoints/latest); leave out --resume to start one"
        )),
        FolderState::Empty | FolderState::Unstarted => Ok(Start::Fresh),
        FolderState::Run if flags.resume => Ok(Start::Resume),
        FolderState::Run | FolderState::Damaged(_) if flags.force => {
            Ok(Start::FreshAfterMovingAside(aside_name(run_dir)))
        }
        FolderState::Run => refuse(format!(
            "{shown} already holds a run (checkpoints/latest): pass --resume to continue it, --force to move it aside (to {}) and start over, or choose another --run-dir",
            aside_name(run_dir).display()
        )),
        FolderState::Damaged(what) => refuse(format!(
            "{shown} holds a run's history ({what}) but no readable checkpoints/latest to continue from: restore checkpoints/latest (from a backup or sync), or pass --force (without --resume) to move the run aside (to {}) and start over",
            aside_name(run_dir).display()
        )),
    }
}

/// At most five names, then how many more.
fn excerpt(names: &[String]) -> String {
    let shown: Vec<&str> = names.iter().take(5).map(String::as_str).collect();
    match names.len() {
        n if n > 5 => format!("{} and {} more", shown.join(", "), n - 5),
        _ => shown.join(", "),
    }
}

/// The first free `DIR.replaced-N` beside `run_dir` (N = 1, 2, …).
pub fn aside_name(run_dir: &Path) -> PathBuf {
    let name = run_dir
        .file_name()
        .map_or("run".into(), |n| n.to_string_lossy().into_owned());
    (1..)
        .map(|n| run_dir.with_file_name(format!("{name}.replaced-{n}")))
        .find(|p| !p.exists())
        .unwrap_or_else(|| run_dir.with_file_name(format!("{name}.replaced")))
}

/// Moves the run in `run_dir` to `to` (one rename: nothing is copied or deleted).
pub fn move_aside(run_dir: &Path, to: &Path) -> Result<(), TrainError> {
    if to.exists() {
        return Err(TrainError::Config(format!(
            "cannot move {} aside: {} already exists",
            run_dir.display(),
            to.display()
        )));
    }
    std::fs::rename(run_dir, to).map_err(io(run_dir))
}

/// One process per run folder: an advisory lock (`flock`) on `DIR/.lock`, which holds the pid of
/// the process training there (the lock `tune` takes on its folder too:
/// [`fairgrasp_types::fs::FolderLock`]). The kernel releases the lock when that process ends,
/// however it ends, so a lock file left by a killed run is stale and is taken over (and said so).
#[derive(Debug)]
pub struct RunLock {
    _lock: FolderLock,
    /// The pid a stale lock file named (a killed run), if any.
    pub stale_pid: Option<String>,
}

impl RunLock {
    /// Takes the lock of `run_dir` (created if missing), or refuses naming the process that
    /// holds it.
    pub fn acquire(run_dir: &Path) -> Result<RunLock, TrainError> {
        match FolderLock::acquire(run_dir, LOCK_FILE, "training", "--run-dir") {
            Ok(lock) => Ok(RunLock {
                stale_pid: lock.stale_pid.clone(),
                _lock: lock,
            }),
            Err(LockRefused::InUse(m) | LockRefused::NotAFile(m)) => Err(TrainError::Config(m)),
            Err(LockRefused::Io(path, e)) => Err(io(&path)(e)),
        }
    }
}
