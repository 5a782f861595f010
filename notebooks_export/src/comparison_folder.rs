//! A comparison folder written whole: `compare.json`, `compare.csv`, the recorded episodes and
//! the report (charts, `report.md`, `report.ipynb`, `replay.html`) into a [`StagedFolder`],
//! moved into place only when all of it is written. `fairgrasp compare` and
//! `fairgrasp.compare` from Python both end here.

use std::path::Path;

use crate::comparison_table::{Comparison, to_csv};
use crate::error::{ReportError, write_file};
use crate::output_folder::StagedFolder;
use crate::report::{Input, write_report};

/// Writes `comparison` and its report into `staged` (which ends up at `shown_as`), with the
/// recorded episodes written by `save_episodes` into the staging folder first, the charts drawn
/// on `threads` threads; commits the folder and returns the files written (relative to it).
pub fn write_comparison_folder(
    staged: StagedFolder,
    comparison: &Comparison,
    shown_as: &Path,
    threads: usize,
    save_episodes: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<Vec<String>, ReportError> {
    let dir = staged.path().to_path_buf();
    save_episodes(&dir).map_err(|what| ReportError::OutputFolder {
        path: dir.join("episodes"),
        what,
    })?;
    write_file(&dir.join("compare.json"), comparison.to_json().as_bytes())?;
    write_file(&dir.join("compare.csv"), to_csv(comparison).as_bytes())?;
    let mut written = vec!["compare.csv".to_string(), "compare.json".to_string()];
    written.extend(write_report(
        &[Input::load(&dir)?],
        &dir,
        shown_as,
        threads,
    )?);
    staged.commit()?;
    Ok(written)
}
