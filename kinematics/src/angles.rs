//! Angle arithmetic shared by the IK solvers.

use std::f64::consts::{PI, TAU};

/// Wraps an angle into (−π, π].
pub fn wrap_pi(angle: f64) -> f64 {
    if angle > -PI && angle <= PI {
        return angle; // the common case: atan2 and acos results
    }
    let a = angle.rem_euclid(TAU);
    if a > PI { a - TAU } else { a }
}
