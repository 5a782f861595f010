//! Reading an episode trajectory (`episode_NNNN.json`) for the charts: the one trajectory type
//! ([`Trajectory`], `fairgrasp_types::trajectory`), checked, with errors naming the file.

use std::path::Path;

pub use fairgrasp_types::trajectory::{Trajectory, TrajectoryRow, TrajectoryScene};

use crate::error::{ReportError, read_text};

/// Reads and checks a trajectory JSON file.
pub fn load(path: &Path) -> Result<Trajectory, ReportError> {
    Trajectory::from_json(&read_text(path)?).map_err(|e| ReportError::malformed(path, e))
}
