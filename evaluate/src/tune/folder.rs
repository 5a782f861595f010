//! A tuning's folder: `tune.json` (what the tuning is), `trials.csv` (every trial so far) and
//! `tuned.toml` (the best setting as a preset fragment). A new folder is claimed by writing
//! `tune.json`; an existing one is resumed only if it holds the same tuning. A tuning of a
//! preset file resumes on the preset its `tune.json` recorded ([`recorded_preset_file`]): a
//! relative file names another file from another working directory.

use std::path::Path;

use fairgrasp_env::EnvConfig;
use fairgrasp_policy::recipe::read::leaf_differences;
use fairgrasp_types::fs::{FolderLock, LockRefused};

use crate::tune::error::TuneError;
use crate::tune::spec::{SpecRecord, TuneSpec};
use crate::tune::trials::{self, Trial};

/// The lock file in a tuning folder (holds the tuning process's pid while it runs; the lock
/// `train` takes on its run folder, [`FolderLock`]).
pub const LOCK_FILE: &str = ".lock";

/// Opens `dir` for `spec` and locks it for this process: a missing or empty folder is claimed
/// (no trials yet); a folder of the same tuning gives its trials back; anything else is
/// refused, nothing in it touched. A folder another process tunes in is refused naming it; a
/// claim that fails (a full disk) leaves no folder behind that this call made.
pub fn open(spec: &TuneSpec, dir: &Path) -> Result<(Vec<Trial>, FolderLock), TuneError> {
    if dir.symlink_metadata().is_ok() && dir.metadata().is_err() {
        return Err(TuneError::file(
            dir,
            "--out is a link that leads nowhere (to itself, or to a missing path): give a new or empty folder".to_string(),
        ));
    }
    if dir.exists() && !dir.is_dir() {
        return Err(TuneError::file(
            dir,
            "--out names a file, not a folder (the file is left alone); give a new or empty folder"
                .to_string(),
        ));
    }
    let spec_path = dir.join("tune.json");
    let existed = dir.exists();
    if existed && !spec_path.exists() && !is_empty(dir)? {
        return Err(TuneError::file(
            dir,
            "not empty and no tune.json: not a tuning folder (its files are left alone); give a new or empty folder".to_string(),
        ));
    }
    let lock = match FolderLock::acquire(dir, LOCK_FILE, "tuning", "--out") {
        Ok(lock) => lock,
        Err(LockRefused::InUse(m) | LockRefused::NotAFile(m)) => {
            return Err(TuneError::Busy(m));
        }
        Err(LockRefused::Io(path, e)) => {
            if !existed {
                remove_claim(dir, true);
            }
            return Err(TuneError::io(&path, e));
        }
    };
    let record = spec.record();
    if spec_path.exists() {
        let saved = SpecRecord::load(&spec_path)?;
        if let Some((what, before, now)) = record.first_difference(&saved) {
            return Err(TuneError::Changed {
                dir: dir.display().to_string(),
                what,
                before,
                now,
            });
        }
        let csv = dir.join("trials.csv");
        let trials = if csv.exists() {
            trials::load(&csv, &spec.names(), &trials::RowRules::of(spec))?
        } else {
            Vec::new()
        };
        return Ok((trials, lock));
    }
    if let Err(e) = record.save(&spec_path) {
        drop(lock);
        // Nothing half-made is left: the lock file, and the folder if this call made it.
        remove_claim(dir, !existed);
        return Err(e);
    }
    Ok((Vec::new(), lock))
}

/// Whether `dir` holds nothing but (perhaps) a tuning's lock file.
fn is_empty(dir: &Path) -> Result<bool, TuneError> {
    let mut entries = std::fs::read_dir(dir).map_err(|e| TuneError::io(dir, e))?;
    Ok(entries.all(|e| e.is_ok_and(|e| e.file_name() == LOCK_FILE)))
}

/// Undoes a claim of `dir` that failed: its lock file, and the folder itself if `made` (this
/// process made it) and it is empty then.
fn remove_claim(dir: &Path, made: bool) {
    std::fs::remove_file(dir.join(LOCK_FILE)).ok();
    if made {
        std::fs::remove_dir(dir).ok();
    }
}

/// The preset a resumed tuning of the preset file `preset` runs on: the config the tuning in
/// `dir` recorded when it started (`tune.json`), with a note when the file `preset` here
/// differs from it (another file of that name from another working directory, or edited since;
/// the note names the first field) or is missing. `None` for a named preset (built into the
/// binary, checked against the record by [`open`]) or a folder with no tuning of that file.
pub fn recorded_preset_file(
    dir: &Path,
    preset: &str,
) -> Result<Option<(EnvConfig, Option<String>)>, TuneError> {
    let spec_path = dir.join("tune.json");
    if !preset.ends_with(".toml") || !spec_path.is_file() {
        return Ok(None);
    }
    let saved = SpecRecord::load(&spec_path)?;
    if saved.preset != preset {
        return Ok(None);
    }
    let config = saved.preset_env(&spec_path)?;
    // The arm simulation is the command's, not the file's.
    let here = fairgrasp_env::config::presets::load(preset)
        .ok()
        .map(|mut here| {
            here.arm.model = config.arm.model;
            here
        });
    let note = match here.as_ref().map(EnvConfig::to_toml) {
        Some(text) if text == saved.preset_config => None,
        Some(text) => {
            let parse = |t: &str| toml::from_str::<toml::Value>(t).ok();
            let field = parse(&saved.preset_config)
                .zip(parse(&text))
                .and_then(|(a, b)| leaf_differences(&a, &b).into_iter().next())
                .map_or("its config".to_string(), |c| c.to_string());
            Some(format!("{preset} here differs ({field})"))
        }
        None => Some(format!("{preset} here is missing or not a valid preset")),
    };
    let note = note.map(|what| {
        format!(
            "the tuning goes on with the preset it started on (recorded in {}); {what} and is not used",
            spec_path.display()
        )
    });
    Ok(Some((config, note)))
}
