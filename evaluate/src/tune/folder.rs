//! A tuning's folder: `tune.json` (what the tuning is), `trials.csv` (every trial so far) and
//! `tuned.toml` (the best setting as a preset fragment). A new folder is claimed by writing
//! `tune.json`; an existing one is resumed only if it holds the same tuning.

use std::path::Path;

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
