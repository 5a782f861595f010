//! The scripted grasp's phases, as the script steps through them and as trajectories record
//! them.

use serde::Serialize;

/// Where the script is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Phase {
    Plan,
    Approach,
    Descend,
    Close,
    Lift,
    Hold,
    /// Gave up: no IK solution, or a phase timed out.
    Failed,
}

impl Phase {
    /// The phase's name as recorded in trajectories (`plan`, `approach`, `descend`, `close`,
    /// `lift`, `hold`, `failed`).
    pub fn name(self) -> &'static str {
        match self {
            Phase::Plan => "plan",
            Phase::Approach => "approach",
            Phase::Descend => "descend",
            Phase::Close => "close",
            Phase::Lift => "lift",
            Phase::Hold => "hold",
            Phase::Failed => "failed",
        }
    }
}
