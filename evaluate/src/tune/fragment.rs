//! A tuned setting as a preset fragment (`tuned.toml`): the control's own table of the preset
//! (`[task.place.search]`, `[control]`) and `[control.tuned.<control>]`, how it was tuned
//! (the env's [`TuningNote`] and, beside it, the tuning's own record: the validation of its
//! finalists and a checksum of the preset as tuned, [`TuneRecord`]).
//! `baseline --tuned` and `compare --tuned` read it into the preset it was tuned on; a fragment
//! of another preset (by content, when it carries the checksum), of another table, of a control
//! without parameters, with a rate outside [0, 1] or a value the preset refuses is refused,
//! naming what. A fragment the user edited is never overwritten ([`write()`]).

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::TuningNote;
use fairgrasp_planner::controls::{Control, control, control_names};
use fairgrasp_types::ArmSimulation;
use fairgrasp_types::fs::{MAX_CONFIG_BYTES, read_text_bounded, write_atomic};
use serde::{Deserialize, Serialize};

use crate::tune::error::TuneError;
use crate::tune::spec::REPORTED_SEED;

/// What `tune` records in `[control.tuned.<control>]` beside the env's [`TuningNote`]: the
/// validation that chose the setting and the preset it was tuned on, by content. Every field
/// is optional on reading: a fragment written before them (none shipped) still reads, checked
/// by the preset's name only.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TuneRecord {
    /// The chosen trial (its objective on the tuning's scenarios is the note's `best`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub best_trial: Option<usize>,
    /// Its objective on the validation's scenarios (a fraction).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_best: Option<f64>,
    /// The validation's scenarios: seed and episodes per finalist.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_seed: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_episodes: Option<usize>,
    /// Finalists re-evaluated, and the env steps they took (part of the note's `env_steps`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finalists: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_env_steps: Option<u64>,
    /// Restarts of the optimiser (a search that stalled, or converged, starts again around the
    /// best trial).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restarts: Option<usize>,
    /// [`preset_checksum`] of the preset tuned on.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub preset_checksum: Option<String>,
}

/// The keys of [`TuneRecord`] in a note's table.
const RECORD_KEYS: [&str; 8] = [
    "best_trial",
    "validation_best",
    "validation_seed",
    "validation_episodes",
    "finalists",
    "validation_env_steps",
    "restarts",
    "preset_checksum",
];

/// FNV-1a, 64 bits, of `bytes` (a checksum, not a signature).
fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// A checksum of `config` as the preset `control` is tuned on (`fnv1a64:<16 hex digits>`): the
/// whole config as TOML but for what a fragment of `control` replaces (its own table and the
/// tuning notes) and the arm simulation (the command's, not the cell's). Two files of the same
/// content have the same checksum, whatever their names, comments and `control`'s setting.
pub fn preset_checksum(config: &EnvConfig, control: &Control) -> String {
    let mut c = config.clone();
    c.arm.model = ArmSimulation::default();
    c.control.tuned.clear();
    let mut value = toml::Value::try_from(&c).unwrap_or(toml::Value::Table(toml::Table::new()));
    if let (Some(table), Some(root)) = (control.table, value.as_table_mut()) {
        remove_at(root, table);
    }
    let text = toml::to_string(&value).unwrap_or_default();
    format!("fnv1a64:{:016x}", fnv1a64(text.as_bytes()))
}

/// Removes the entry at dotted `path` of `root`, if there is one.
fn remove_at(root: &mut toml::Table, path: &str) {
    let mut keys: Vec<&str> = path.split('.').collect();
    let last = keys.pop().unwrap_or_default();
    let mut here = root;
    for k in keys {
        match here.get_mut(k).and_then(toml::Value::as_table_mut) {
            Some(t) => here = t,
            None => return,
        }
    }
    here.remove(last);
}

/// The first line of a fragment's header that `tune` checks its own writing by.
const WRITTEN_MARK: &str = "# written by `fairgrasp tune`, checksum ";

/// `text` with its checksum line in place: the checksum of every other line.
fn sealed(text: &str) -> String {
    let sum = fnv1a64(text.as_bytes());
    format!(
        "{WRITTEN_MARK}fnv1a64:{sum:016x} (an edit changes it; `tune` never overwrites an edited fragment)\n{text}"
    )
}

/// Whether `text` is a fragment exactly as `tune` wrote it (its checksum line matches).
fn as_written(text: &str) -> bool {
    let Some((first, rest)) = text.split_once('\n') else {
        return false;
    };
    first.starts_with(WRITTEN_MARK) && sealed(rest) == text
}

/// Env steps in the unit that reads: `624 env steps`, `3.01 M env steps`.
pub fn env_steps_text(n: u64) -> String {
    if n < 100_000 {
        format!("{n} env steps")
    } else {
        format!("{:.2} M env steps", n as f64 / 1e6)
    }
}

/// A note's line, with env steps in the unit that reads (the note's own summary always says
/// millions): `CMA-ES (cmaes 0.2.2), 96 trials × 150 episodes of seed 11, 624 env steps`.
pub fn summary(note: &TuningNote) -> String {
    format!(
        "{}, {} trials × {} episodes of seed {}, {}",
        note.optimiser,
        note.trials,
        note.episodes_per_trial,
        note.scenario_seed,
        env_steps_text(note.env_steps)
    )
}

/// Where [`write()`] put the fragment.
#[derive(Clone, Debug, PartialEq)]
pub struct Written {
    pub path: PathBuf,
    /// The fragment at the path asked for, edited since `tune` wrote it, was kept.
    pub kept_edited: Option<PathBuf>,
}

/// The table at dotted `path` in `value`, if there is one.
fn table_at<'a>(value: &'a toml::Value, path: &str) -> Option<&'a toml::Value> {
    path.split('.').try_fold(value, |v, key| v.get(key))
}

/// Puts `inner` at dotted `path` in `root`, creating the tables on the way.
fn put_at(root: &mut toml::Table, path: &str, inner: toml::Value) {
    let mut keys: Vec<&str> = path.split('.').collect();
    let last = keys.pop().unwrap_or_default();
    let mut here = root;
    for k in keys {
        here = here
            .entry(k)
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .expect("a table on the way");
    }
    here.insert(last.to_string(), inner);
}

/// Writes the fragment of `control`'s settings in `tuned`, its `note` and `record`, atomically
/// to `path` — unless a fragment there was edited since `tune` wrote it (or was not written by
/// it): that one is kept, and the new one written beside it (`tuned.new.toml`).
pub fn write(
    path: &Path,
    tuned: &EnvConfig,
    control: &Control,
    note: &TuningNote,
    record: &TuneRecord,
) -> Result<Written, TuneError> {
    let whole = toml::Value::try_from(tuned).map_err(|e| TuneError::file(path, e.to_string()))?;
    let mut out = toml::Table::new();
    if let Some(table) = control.table {
        let mut settings = table_at(&whole, table)
            .cloned()
            .unwrap_or(toml::Value::Table(toml::Table::new()));
        // `[control]` also holds the notes: the fragment carries this control's only.
        if let Some(t) = settings.as_table_mut() {
            t.remove("tuned");
        }
        put_at(&mut out, table, settings);
    }
    let mut note_value =
        toml::Value::try_from(note).map_err(|e| TuneError::file(path, e.to_string()))?;
    let record_value =
        toml::Value::try_from(record).map_err(|e| TuneError::file(path, e.to_string()))?;
    if let (Some(n), Some(r)) = (note_value.as_table_mut(), record_value.as_table()) {
        n.extend(r.clone());
    }
    put_at(
        &mut out,
        &format!("control.tuned.{}", control.cli),
        note_value,
    );
    let validation = match (
        record.validation_best,
        record.validation_seed,
        record.validation_episodes,
    ) {
        (Some(v), Some(seed), Some(n)) => {
            format!("; on validation, {v:.3} ({n} episodes of seed {seed})")
        }
        _ => String::new(),
    };
    let header = format!(
        "# `{}` tuned on `{}` by `fairgrasp tune`: {} ({}, best {:.3}{validation}).\n# Read it with `fairgrasp baseline --tuned FILE` or `fairgrasp compare --tuned FILE`.\n\n",
        control.cli,
        note.preset,
        summary(note),
        note.objective,
        note.best
    );
    let text = sealed(
        &(header
            + &toml::to_string_pretty(&out).map_err(|e| TuneError::file(path, e.to_string()))?),
    );
    let mut target = path.to_path_buf();
    let mut kept_edited = None;
    if path.exists() {
        let old = read_text_bounded(path, MAX_CONFIG_BYTES).ok();
        let same = old.as_deref() == Some(text.as_str());
        if !same && !old.as_deref().is_some_and(as_written) {
            kept_edited = Some(path.to_path_buf());
            target = path.with_file_name("tuned.new.toml");
        }
    }
    write_atomic(&target, text.as_bytes()).map_err(|e| TuneError::io(&target, e))?;
    Ok(Written {
        path: target,
        kept_edited,
    })
}

/// Reads the fragment at `path` into `config` (the preset `preset`, as named on the command
/// line): its control's table replaces the preset's, its note joins `[control.tuned]`. Returns
/// the control. With several fragments for one preset, [`apply_to`] with the preset as read.
pub fn apply(
    config: &mut EnvConfig,
    preset: &str,
    path: &Path,
) -> Result<&'static Control, TuneError> {
    let base = config.clone();
    apply_to(config, preset, &base, path)
}

/// [`apply`], the fragment's `preset_checksum` checked against `base`, the preset as read
/// (before any fragment).
pub fn apply_to(
    config: &mut EnvConfig,
    preset: &str,
    base: &EnvConfig,
    path: &Path,
) -> Result<&'static Control, TuneError> {
    let text = read_text_bounded(path, MAX_CONFIG_BYTES).map_err(|e| TuneError::io(path, e))?;
    let fragment: toml::Table = toml::from_str(&text).map_err(|e| {
        let where_and_why = fairgrasp_env::config::validate::toml_error_message(&text, &e);
        TuneError::file(path, format!("not TOML: {where_and_why}"))
    })?;
    let refuse = |m: String| TuneError::file(path, m);
    let notes = fragment
        .get("control")
        .and_then(|c| c.get("tuned"))
        .and_then(toml::Value::as_table)
        .ok_or_else(|| {
            refuse(
                "no [control.tuned.<control>] table: not a fragment `fairgrasp tune` wrote".into(),
            )
        })?;
    let [(name, note)] = notes.iter().collect::<Vec<_>>()[..] else {
        return Err(refuse(format!(
            "[control.tuned] names {} controls; a fragment holds one",
            notes.len()
        )));
    };
    let task = config.task.kind;
    let c = control(task, name).ok_or_else(|| {
        refuse(format!(
            "[control.tuned.{name}]: not a control of this preset's task ({})",
            control_names(task).join(", ")
        ))
    })?;
    if c.params.is_empty() {
        return Err(refuse(format!(
            "[control.tuned.{name}]: `{name}` has no parameters to tune: a fragment of it sets nothing"
        )));
    }
    let mut note_table = note.as_table().cloned().ok_or_else(|| {
        refuse(format!(
            "[control.tuned.{name}]: not a table of how it was tuned"
        ))
    })?;
    let mut record_table = toml::Table::new();
    for key in RECORD_KEYS {
        if let Some(v) = note_table.remove(key) {
            record_table.insert(key.to_string(), v);
        }
    }
    let note: TuningNote = toml::Value::Table(note_table)
        .try_into()
        .map_err(|e| refuse(format!("[control.tuned.{name}]: {e}")))?;
    let record: TuneRecord = toml::Value::Table(record_table)
        .try_into()
        .map_err(|e| refuse(format!("[control.tuned.{name}]: {e}")))?;
    check_note(&note, &record).map_err(|m| refuse(format!("[control.tuned.{name}]: {m}")))?;
    let (wanted, _) = fairgrasp_env::config::presets::current_name(preset);
    let checksum = preset_checksum(base, c);
    match &record.preset_checksum {
        Some(sum) if *sum != checksum => {
            return Err(refuse(format!(
                "tuned on preset `{}` (checksum {sum}), which conflicts with the preset run, `{preset}` (checksum {checksum}): its content differs, and a setting tuned for one cell is not another's; tune on `{preset}`",
                note.preset
            )));
        }
        // The same content, whatever the file is called now.
        Some(_) => {}
        None if note.preset != wanted && note.preset != preset => {
            return Err(refuse(format!(
                "tuned on preset `{}`, which conflicts with the preset run, `{preset}`: a setting tuned for one cell is not another's; tune on `{preset}`",
                note.preset
            )));
        }
        None => {}
    }
    check_only_its_table(&fragment, c).map_err(refuse)?;
    let mut whole = toml::Value::try_from(&*config).map_err(|e| refuse(e.to_string()))?;
    if let Some(table) = c.table {
        let mut settings = table_at(&toml::Value::Table(fragment.clone()), table)
            .cloned()
            .ok_or_else(|| {
                refuse(format!(
                    "no [{table}] table: the control's settings are missing"
                ))
            })?;
        // `[control]`'s other notes stay.
        let kept = table_at(&whole, table)
            .and_then(|old| old.get("tuned"))
            .cloned();
        if let (Some(t), Some(tuned)) = (settings.as_table_mut(), kept) {
            t.insert("tuned".into(), tuned);
        }
        if let Some(root) = whole.as_table_mut() {
            put_at(root, table, settings);
        }
    }
    let mut merged: EnvConfig = whole.try_into().map_err(|e: toml::de::Error| {
        refuse(format!("does not fit the preset: {}", e.message()))
    })?;
    merged.control.tuned.insert(name.clone(), note);
    merged
        .validate()
        .map_err(|e| refuse(format!("the preset refuses its setting: {e}")))?;
    *config = merged;
    Ok(c)
}

/// A note's figures as a tuning makes them: rates in [0, 1], at least one trial of at least one
/// episode, a validation on scenarios of its own, never the reported seed.
fn check_note(note: &TuningNote, record: &TuneRecord) -> Result<(), String> {
    let rate = |what: &str, v: f64| {
        if (0.0..=1.0).contains(&v) {
            Ok(())
        } else if v.abs() >= 1e9 {
            Err(format!(
                "{what} = {v:e}: a rate of successes lies in [0, 1]"
            ))
        } else {
            Err(format!("{what} = {v}: a rate of successes lies in [0, 1]"))
        }
    };
    rate("best", note.best)?;
    if let Some(v) = record.validation_best {
        rate("validation_best", v)?;
    }
    if note.trials == 0 || note.episodes_per_trial == 0 {
        return Err(format!(
            "trials = {}, episodes_per_trial = {}: a tuning runs at least one trial of one episode",
            note.trials, note.episodes_per_trial
        ));
    }
    if note.scenario_seed == REPORTED_SEED || record.validation_seed == Some(REPORTED_SEED) {
        return Err(format!(
            "tuned or validated on seed {REPORTED_SEED}, the seed results are reported on: a setting chosen on it is no held-out result"
        ));
    }
    if record.validation_seed == Some(note.scenario_seed) {
        return Err(format!(
            "validation_seed = {}: the tuning's own scenarios, not a validation",
            note.scenario_seed
        ));
    }
    if let (Some(t), Some(steps)) = (record.best_trial, record.validation_env_steps)
        && (t >= note.trials || steps > note.env_steps)
    {
        return Err(format!(
            "best_trial = {t} of {} trials, validation_env_steps = {steps} of {}: not the figures of one tuning",
            note.trials, note.env_steps
        ));
    }
    Ok(())
}

/// Refuses a fragment that sets anything but `control`'s table and its note.
fn check_only_its_table(fragment: &toml::Table, c: &Control) -> Result<(), String> {
    let mut allowed: Vec<String> = vec!["control.tuned".into()];
    allowed.extend(c.table.map(String::from));
    let mut leaves = Vec::new();
    collect_paths(fragment, "", &allowed, &mut leaves);
    match leaves.first() {
        None => Ok(()),
        Some(key) => Err(format!(
            "sets `{key}`, which `{}` does not tune (it tunes [{}]): a fragment may set its control's table only",
            c.cli,
            c.table.unwrap_or("nothing")
        )),
    }
}

/// Dotted keys of `t` (under `prefix`) that are not inside one of `allowed`.
fn collect_paths(t: &toml::Table, prefix: &str, allowed: &[String], out: &mut Vec<String>) {
    for (k, v) in t {
        let path = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        if allowed
            .iter()
            .any(|a| path == *a || path.starts_with(&format!("{a}.")))
        {
            continue;
        }
        let inside = allowed.iter().any(|a| a.starts_with(&format!("{path}.")));
        match v.as_table() {
            Some(sub) if inside => collect_paths(sub, &path, allowed, out),
            _ => out.push(path),
        }
    }
}
