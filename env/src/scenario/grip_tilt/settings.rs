//! The grip tilt's bounds and rule (`[task.place] grip_tilt`, a `[min, max]` range of angles
//! \[rad\]).

use crate::config::check::{Bounds, RangeBounds, check_range};
use crate::config::error::ConfigError;
use crate::config::range::Range;

/// How far above the table \[m\] the cube's bottom must be carried before it turns in the grip
/// (`task.place.grip_tilt`): clear of the table, so that the turn cannot push it into anything.
pub const GRIP_TILT_LIFT: f64 = 0.02;

/// The largest grip tilt a config may ask for \[rad\] (20°).
pub const MAX_GRIP_TILT: f64 = 0.35;

/// Refuses a grip tilt range that is not finite, ordered, non-negative and within
/// [`MAX_GRIP_TILT`], naming `task.place.grip_tilt`.
pub fn check_grip_tilt(grip_tilt: &Range) -> Result<(), ConfigError> {
    check_range(
        grip_tilt,
        "task.place.grip_tilt",
        RangeBounds::new(
            Bounds::closed(0.0, MAX_GRIP_TILT).unit("rad"),
            "(20°: more and the turned cube reaches the palm)",
        ),
    )
}
