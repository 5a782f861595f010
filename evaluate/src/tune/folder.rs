//! A tuning's folder: `tune.json` (what the tuning is), `trials.csv` (every trial so far) and
//! `tuned.toml` (the best setting as a preset fragment). A new folder is claimed by writing
//! `tune.json`; an existing one is resumed only if it holds the same tuning. A tuning of a
//! preset file resumes on the preset its `tune.json` recorded ([`recorded_preset_file`]): a
//! relative file names another file from another working directory.

use std::path::Path;

use fairgrasp_env::EnvConfig;
use fairgrasp_policy::recipe::read::leaf_differences;

use crate::tune::error::TuneError;
use crate::tune::spec::{SpecRecord, TuneSpec};
use crate::tune::trials::{self, Trial};

/// Opens `dir` for `spec`: a missing or empty folder is claimed (no trials yet); a folder of
/// the same tuning gives its trials back; anything else is refused, nothing in it touched.
pub fn open(spec: &TuneSpec, dir: &Path) -> Result<Vec<Trial>, TuneError> {
    let record = spec.record();
    let spec_path = dir.join("tune.json");
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
        return if csv.exists() {
            trials::load(&csv, &spec.names())
        } else {
            Ok(Vec::new())
        };
    }
    if dir.exists() && !dir.is_dir() {
        return Err(TuneError::file(
            dir,
            "--out names a file, not a folder (the file is left alone); give a new or empty folder"
                .to_string(),
        ));
    }
    if dir.exists() {
        let empty = std::fs::read_dir(dir)
            .map_err(|e| TuneError::io(dir, e))?
            .next()
            .is_none();
        if !empty {
            return Err(TuneError::file(
                dir,
                "not empty and no tune.json: not a tuning folder (its files are left alone); give a new or empty folder".to_string(),
            ));
        }
    }
    record.save(&spec_path)?;
    Ok(Vec::new())
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
