//! A checkpoint that cannot be read: the file and the reason.

use std::path::Path;

/// A checkpoint that cannot be read, with the file and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("checkpoint {path}: {reason}")]
pub struct CheckpointError {
    pub path: String,
    pub reason: String,
}

/// A [`CheckpointError`] for `path`.
pub fn err(path: &Path, reason: impl std::fmt::Display) -> CheckpointError {
    CheckpointError {
        path: path.display().to_string(),
        reason: reason.to_string(),
    }
}
