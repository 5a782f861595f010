//! What can stop a tuning, each naming what was wrong.

use std::path::Path;

/// Why a tuning did not run or stopped.
#[derive(Debug, thiserror::Error)]
pub enum TuneError {
    /// The request itself (control, parameter, range, budget) is not one that can run.
    #[error("{0}")]
    Request(String),
    /// A file of the tuning folder is unreadable or not what it should be.
    #[error("{path}: {message}")]
    File { path: String, message: String },
    /// The folder holds a tuning of something else: resuming it would mix two tunings.
    #[error(
        "{dir}: holds a tuning whose {what} was {before}, not {now}; tune into another folder (--out), or delete it to start over"
    )]
    Changed {
        dir: String,
        what: &'static str,
        before: String,
        now: String,
    },
    /// The folder is not this process's to use now (another holds its lock), as one line.
    #[error("{0}")]
    Busy(String),
    /// The env could not run an episode.
    #[error(transparent)]
    Env(#[from] fairgrasp_env::EnvError),
}

impl TuneError {
    pub(crate) fn io(path: &Path, e: std::io::Error) -> Self {
        Self::file(path, e.to_string())
    }

    pub(crate) fn file(path: &Path, message: String) -> Self {
        Self::File {
            path: path.display().to_string(),
            message,
        }
    }
}
