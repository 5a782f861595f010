//! The `nudged` family's settings (`[randomization] nudge`), plain data, and their rules.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, RangeBounds, check, check_in, check_range};
use crate::config::error::ConfigError;
use crate::config::range::Range;

/// How a cube is nudged: once per episode, by a push drawn from the scenario seed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NudgeConfig {
    /// Push length on the table \[m\], drawn uniformly (0 < min ≤ max ≤ [`MAX_NUDGE`]).
    pub distance: Range,
    /// Env step (0-based, before that step's action) at which the push happens, drawn
    /// uniformly in `[min, max]`.
    pub step: [usize; 2],
    /// The push is skipped unless the TCP is at least this far from the cube centre \[m\], before
    /// and after it (≥ [`MIN_TCP_DISTANCE`]: 5 cm of gap plus the cube's half-diagonal and the
    /// open fingers' reach).
    pub min_tcp_distance: f64,
}

/// Longest accepted push \[m\].
pub const MAX_NUDGE: f64 = 0.15;
/// Smallest accepted `min_tcp_distance` \[m\].
pub const MIN_TCP_DISTANCE: f64 = 0.12;

impl NudgeConfig {
    /// Refuses a push that cannot mean what it says, naming the field: `max_steps` is
    /// `task.max_steps` (the push must come before the episode ends), `position` is
    /// `randomization.position` (the push stays in the position's radius range).
    pub fn check(&self, max_steps: usize, position: bool) -> Result<(), ConfigError> {
        check_range(
            &self.distance,
            "randomization.nudge.distance",
            RangeBounds::new(
                Bounds::above_to(0.0, MAX_NUDGE).unit("m"),
                "(MAX_NUDGE, 15 cm: a nudge during the approach, not a throw across the table)",
            ),
        )?;
        check_range(
            &self.step,
            "randomization.nudge.step",
            RangeBounds::new(
                Bounds::from_below(0.0, max_steps as f64).unit("steps"),
                "(before the episode's last step, task.max_steps)",
            ),
        )?;
        check_in(
            self.min_tcp_distance,
            "randomization.nudge.min_tcp_distance",
            Bounds::at_least(MIN_TCP_DISTANCE).unit("m"),
            "(5 cm of gap plus the cube and the open fingers)",
        )?;
        check(
            position,
            "randomization.nudge",
            "set",
            "needs randomization.position = true (the push stays in its radius range)",
        )
    }
}
