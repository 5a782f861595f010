//! What a resume reads again besides its recipe, held to what the run started with.
//!
//! The recipe itself is compared with the run's `config.toml`
//! ([`crate::run::resume::check_config`]), and a preset file is trained on from the run's copy
//! (`env.toml`, [`crate::run::resume::training_config`]). Everything else a recipe names is
//! found again on a resume, from wherever the command runs: a `mix` preset file (a relative path
//! names another file in another folder), a preset built into the binary (another build may
//! read it differently), a `[kickstart]` teacher (a relative folder names another folder; a run
//! folder's `best` may have been replaced since). The run keeps what each of them was when it
//! started in `RUN/inputs.toml` ([`INPUTS_RECORD`]): every preset's env as the run's
//! evaluations see it, and every teacher's folder and checksum. A resume on which one differs
//! is refused naming it and what differs, unless `--accept-config-changes` is given (then the
//! difference is recorded in `config_changes.log` and the record follows).

use std::path::{Path, PathBuf};

use fairgrasp_policy::checkpoint::verify::folder_checksum_text;
use fairgrasp_policy::recipe::EnvFor;
use fairgrasp_policy::recipe::read::leaf_differences;
use fairgrasp_policy::shipped::{ShippedPolicy, checkpoint_folder};
use fairgrasp_types::fs::{MAX_CONFIG_BYTES, MAX_DATA_BYTES, read_bounded, read_text_bounded};
use fairgrasp_types::write_atomic;
use serde::{Deserialize, Serialize};

use crate::run::config::TrainConfig;
use crate::run::error::{TrainError, io};

/// The record's name inside the run folder.
pub const INPUTS_RECORD: &str = "inputs.toml";

/// What the run's recipe names, as it read when the run started (or when a resume last
/// accepted a change).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputsRecord {
    /// Every preset the run trains on, `preset` then `mix`, in the recipe's order.
    pub presets: Vec<PresetRecord>,
    /// Every `[kickstart]` teacher, in the recipe's order (none without `[kickstart]`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub teachers: Vec<TeacherRecord>,
}

/// One preset: its name as the recipe gives it and its env as evaluations see it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PresetRecord {
    pub name: String,
    /// The preset's `EnvConfig` (without the recipe's `[env]` table, which is the recipe's).
    pub env: toml::Table,
}

/// One teacher: its name as the recipe gives it, the checkpoint folder it named (absolute) and
/// the checksum of that checkpoint's `meta.json` and `model.bpk`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TeacherRecord {
    pub name: String,
    pub folder: String,
    pub checksum: String,
}

impl InputsRecord {
    /// What `config` names as it reads now, from the working directory (a preset file from the
    /// run's copy when `config.env_snapshot` says so).
    pub fn now(config: &TrainConfig) -> Result<Self, TrainError> {
        let envs = config
            .env_configs(EnvFor::Evaluation)
            .map_err(TrainError::Config)?;
        let names = std::iter::once(&config.preset).chain(&config.mix);
        let presets = names
            .zip(envs)
            .map(|(name, env)| {
                let env = toml::Table::try_from(&env)
                    .map_err(|e| TrainError::Config(format!("preset {name}: {e}")))?;
                Ok(PresetRecord {
                    name: name.clone(),
                    env,
                })
            })
            .collect::<Result<_, TrainError>>()?;
        let teachers = config
            .kickstart
            .iter()
            .flat_map(|k| &k.teachers)
            .map(String::as_str)
            .map(teacher_now)
            .collect::<Result<_, _>>()?;
        Ok(Self { presets, teachers })
    }

    /// The record in `run_dir`, or `None` if the run has none (started by a fairgrasp that
    /// kept no record); a record that cannot be read is refused naming the file.
    pub fn load(run_dir: &Path) -> Result<Option<Self>, TrainError> {
        let path = run_dir.join(INPUTS_RECORD);
        let text = match read_text_bounded(&path, MAX_CONFIG_BYTES) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(io(&path)(e)),
        };
        toml::from_str(&text).map(Some).map_err(|e| {
            TrainError::Config(format!(
                "{}: not the record of a run's presets and teachers ({}): restore it, or delete it to record them as they read now",
                path.display(),
                e.message()
            ))
        })
    }

    /// Writes the record into `run_dir`, atomically.
    pub fn save(&self, run_dir: &Path) -> Result<(), TrainError> {
        let path = run_dir.join(INPUTS_RECORD);
        let body = toml::to_string_pretty(self)
            .map_err(|e| TrainError::Config(format!("{}: {e}", path.display())))?;
        let text = format!(
            "# What this run's recipe names, as it read when the run started (written by fairgrasp train):\n# a resume that finds any of it changed is refused naming what differs.\n\n{body}"
        );
        write_atomic(&path, text.as_bytes()).map_err(io(&path))
    }

    /// How `now` differs from `self` (the run's record), one entry per preset or teacher, as
    /// `what: before → now`. A preset or teacher whose name changed is the recipe's change
    /// (which [`crate::run::resume::check_config`] lists), not listed here.
    pub fn differences(&self, now: &Self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, (old, new)) in self.presets.iter().zip(&now.presets).enumerate() {
            if old.name != new.name {
                continue;
            }
            let which = match i {
                0 => format!("preset `{}`", new.name),
                m => format!("mix preset `{}` (mix[{}])", new.name, m - 1),
            };
            if let Some(d) = first_difference(&old.env, &new.env) {
                out.push(format!(
                    "{which} reads differently here than when the run started: {d}"
                ));
            }
        }
        for (i, (old, new)) in self.teachers.iter().zip(&now.teachers).enumerate() {
            let which = format!("kickstart.teachers[{i}] `{}`", new.name);
            if old.name != new.name {
                continue;
            }
            if old.folder != new.folder {
                out.push(format!(
                    "{which} names {} here, the run started with {}",
                    new.folder, old.folder
                ));
            } else if old.checksum != new.checksum {
                out.push(format!(
                    "{which}: the checkpoint in {} was replaced since the run started (checksum {} → {})",
                    new.folder, old.checksum, new.checksum
                ));
            }
        }
        out
    }
}

/// The first leaf in which two env tables differ, as `field: before → now` (and how many more
/// fields differ).
pub fn first_difference(before: &toml::Table, now: &toml::Table) -> Option<String> {
    let differing = leaf_differences(
        &toml::Value::Table(before.clone()),
        &toml::Value::Table(now.clone()),
    );
    let first = differing.first()?;
    Some(match differing.len() {
        1 => first.to_string(),
        n => format!("{first} (and {} more fields)", n - 1),
    })
}

/// A teacher as it reads now: the folder its name gives (absolute) and its checksum. The error
/// of a teacher that cannot be found names it.
fn teacher_now(name: &str) -> Result<TeacherRecord, TrainError> {
    let bad = |why: String| TrainError::Config(format!("kickstart.teachers: {name}: {why}"));
    let dir = checkpoint_folder(name).map_err(bad)?;
    let folder = if ShippedPolicy::named(name).is_some() {
        // A shipped policy follows the binary: its unpacked folder's place is not the run's.
        format!("the shipped policy {name}")
    } else {
        absolute(&dir).display().to_string()
    };
    let mut files = Vec::new();
    for file in ["meta.json", "model.bpk"] {
        let path = dir.join(file);
        // `checkpoint_folder` also takes a folder whose save was cut (only `.old` holds it):
        // its checksum is that of the copy training loads.
        let path = if path.is_file() {
            path
        } else {
            dir.with_extension("old").join(file)
        };
        files.push((
            file,
            read_bounded(&path, MAX_DATA_BYTES).map_err(io(&path))?,
        ));
    }
    let refs: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    let checksum = folder_checksum_text(&refs)
        .split_whitespace()
        .next()
        .unwrap_or_default()
        .to_string();
    Ok(TeacherRecord {
        name: name.to_string(),
        folder,
        checksum,
    })
}

/// `path` made absolute and free of `..` where the file system allows (else joined to the
/// working directory as it is).
fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path)
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf())
}

/// Holds a resume to the run's record: the differences between it and what `config` names now
/// (empty when all is as it was). A run without a record (started by an older fairgrasp) gets
/// one from what reads now, and a note says so.
pub fn changes_since_start(run_dir: &Path, now: &InputsRecord) -> Result<Vec<String>, TrainError> {
    match InputsRecord::load(run_dir)? {
        Some(saved) => Ok(saved.differences(now)),
        None => {
            eprintln!(
                "note: {} keeps no record of the presets and teachers it started with (a run from an older fairgrasp): they are recorded as they read now in {INPUTS_RECORD}, and later resumes are held to them",
                run_dir.display()
            );
            Ok(Vec::new())
        }
    }
}
