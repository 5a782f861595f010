//! A tuned setting as a preset fragment (`tuned.toml`): the control's own table of the preset
//! (`[task.place.search]`, `[control]`) and `[control.tuned.<control>]`, how it was tuned.
//! `baseline --tuned` and `compare --tuned` read it into the preset it was tuned on; a fragment
//! of another preset, of another table, or with a value the preset refuses is refused, naming
//! what.

use std::path::Path;

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::TuningNote;
use fairgrasp_planner::controls::{Control, control, control_names};
use fairgrasp_types::fs::{MAX_CONFIG_BYTES, read_text_bounded, write_atomic};

use crate::tune::error::TuneError;

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

/// Writes the fragment of `control`'s settings in `tuned` and its `note`, atomically.
pub fn write(
    path: &Path,
    tuned: &EnvConfig,
    control: &Control,
    note: &TuningNote,
) -> Result<(), TuneError> {
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
    let note_value =
        toml::Value::try_from(note).map_err(|e| TuneError::file(path, e.to_string()))?;
    put_at(
        &mut out,
        &format!("control.tuned.{}", control.cli),
        note_value,
    );
    let header = format!(
        "# `{}` tuned on `{}` by `fairgrasp tune`: {} ({}, best {:.3}).\n# Read it with `fairgrasp baseline --tuned FILE` or `fairgrasp compare --tuned FILE`.\n\n",
        control.cli,
        note.preset,
        note.summary(),
        note.objective,
        note.best
    );
    let text =
        header + &toml::to_string_pretty(&out).map_err(|e| TuneError::file(path, e.to_string()))?;
    write_atomic(path, text.as_bytes()).map_err(|e| TuneError::io(path, e))
}

/// Reads the fragment at `path` into `config` (the preset `preset`, as named on the command
/// line): its control's table replaces the preset's, its note joins `[control.tuned]`. Returns
/// the control.
pub fn apply(
    config: &mut EnvConfig,
    preset: &str,
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
    let note: TuningNote = note
        .clone()
        .try_into()
        .map_err(|e| refuse(format!("[control.tuned.{name}]: {e}")))?;
    let (wanted, _) = fairgrasp_env::config::presets::current_name(preset);
    if note.preset != wanted && note.preset != preset {
        return Err(refuse(format!(
            "tuned on preset `{}`, which conflicts with the preset run, `{preset}`: a setting tuned for one cell is not another's; tune on `{preset}`",
            note.preset
        )));
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
