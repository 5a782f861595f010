//! Why a comparison could not run ([`CompareError`]).

use std::path::PathBuf;

use fairgrasp_env::EnvError;

use fairgrasp_policy::checkpoint::CheckpointError;

/// Why a comparison could not run.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// The request itself is wrong (a repeated preset, an episode index out of range, …).
    #[error("{0}")]
    Request(String),
    #[error(transparent)]
    Checkpoint(#[from] CheckpointError),
    #[error("preset `{preset}`: {message}")]
    Preset { preset: String, message: String },
    #[error(transparent)]
    Env(#[from] EnvError),
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
}
