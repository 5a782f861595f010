//! Reading an episode trajectory (`episode_NNNN.json`, or a comparison's compact
//! `<stem>.json.gz`) for the charts: the one trajectory type ([`Trajectory`],
//! `fairgrasp_types::trajectory`), checked, with errors naming the file.

use std::path::Path;

pub use fairgrasp_types::trajectory::{Trajectory, TrajectoryRow, TrajectoryScene};

use fairgrasp_types::fs::{MAX_DATA_BYTES, read_bounded};

use crate::error::ReportError;

/// Reads and checks a trajectory file, JSON or gzipped JSON.
pub fn load(path: &Path) -> Result<Trajectory, ReportError> {
    let bytes = read_bounded(path, MAX_DATA_BYTES).map_err(|e| ReportError::io(path, e))?;
    Trajectory::from_bytes(&bytes, MAX_DATA_BYTES).map_err(|e| ReportError::malformed(path, e))
}
