//! One episode as a replay shows it: the method, the scenario and the recorded trajectory.

use fairgrasp_types::Outcome;
use fairgrasp_types::trajectory::Trajectory;

/// One episode in a replay.
#[derive(Clone, Debug)]
pub struct ReplayEpisode<'a> {
    /// The method's name (`scripted baseline`, `residual PPO: residual_hard`, …).
    pub method: String,
    pub preset: String,
    /// Index of the scenario in the preset's seeded set.
    pub episode: usize,
    /// How it ended (else the trajectory's own record).
    pub outcome: Option<Outcome>,
    pub trajectory: &'a Trajectory,
}
