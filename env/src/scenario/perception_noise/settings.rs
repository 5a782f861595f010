//! The rules of the perception noise's settings (`randomization.observed_position_noise`,
//! `randomization.observed_yaw_noise`).

use crate::config::check::{Bounds, check_in};
use crate::config::error::ConfigError;

/// Refuses a noise level that is not finite or beyond what a scenario means (the workspace is
/// 0.25–0.45 m from the base), naming the field: position in [0, 0.2] m, yaw in [0, π] rad.
pub fn check_perception_noise(position: f64, yaw: f64) -> Result<(), ConfigError> {
    check_in(
        position,
        "randomization.observed_position_noise",
        Bounds::closed(0.0, 0.2).unit("m"),
        "(hard: 0.01)",
    )?;
    check_in(
        yaw,
        "randomization.observed_yaw_noise",
        Bounds::closed(0.0, std::f64::consts::PI).unit("rad"),
        "(π; hard: 0.1745, 10°)",
    )
}
