//! The one error type of the report crate: every variant names the file it is about.

use std::path::{Path, PathBuf};

/// Why a report, chart or table could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A folder given as input holds none of the files a run or comparison folder has.
    #[error("{path}: {what}")]
    NotAReportInput { path: PathBuf, what: String },
    /// A file exists but its content is not what fairgrasp writes.
    #[error("{path}: {what}")]
    Malformed { path: PathBuf, what: String },
    /// The output folder may not be written (it is not ours to replace, it is an input, or its
    /// parent is not writable), or the finished folder could not be moved into place.
    #[error("{path}: {what}")]
    OutputFolder { path: PathBuf, what: String },
    /// plotters or the image encoder failed, or the chart cannot be drawn from these data.
    #[error("chart {path}: {what}")]
    Chart { path: PathBuf, what: String },
    /// The 3D replay cannot be made (nothing to replay, or an episode it cannot pack).
    #[error("replay: {0}")]
    ReplayUnavailable(String),
}

impl ReportError {
    pub(crate) fn io(path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            path: path.to_path_buf(),
            source,
        }
    }

    pub(crate) fn malformed(path: &Path, what: impl Into<String>) -> Self {
        Self::Malformed {
            path: path.to_path_buf(),
            what: what.into(),
        }
    }

    pub(crate) fn chart(path: &Path, what: impl std::fmt::Display) -> Self {
        Self::Chart {
            path: path.to_path_buf(),
            what: what.to_string(),
        }
    }
}

/// Reads a text file, naming it on failure.
pub(crate) fn read_text(path: &Path) -> Result<String, ReportError> {
    fairgrasp_types::fs::read_text_bounded(path, fairgrasp_types::fs::MAX_DATA_BYTES)
        .map_err(|e| ReportError::io(path, e))
}

/// [`fairgrasp_types::write_atomic`], naming the file on failure.
pub(crate) fn write_file(path: &Path, bytes: &[u8]) -> Result<(), ReportError> {
    fairgrasp_types::write_atomic(path, bytes).map_err(|e| ReportError::io(path, e))
}
