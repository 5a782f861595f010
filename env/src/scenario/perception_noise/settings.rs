//! The rules of the perception noise's settings (`randomization.observed_position_noise`,
//! `randomization.observed_yaw_noise`).

use crate::config::check::check;
use crate::config::error::ConfigError;

/// Refuses a noise level that is not finite or beyond what a scenario means (the workspace is
/// 0.25–0.45 m from the base), naming the field: position in [0, 0.2] m, yaw in [0, π] rad.
pub fn check_perception_noise(position: f64, yaw: f64) -> Result<(), ConfigError> {
    for (value, field, bound, rule) in [
        (
            position,
            "randomization.observed_position_noise",
            0.2,
            "must be in [0, 0.2] m (hard: 0.01)",
        ),
        (
            yaw,
            "randomization.observed_yaw_noise",
            std::f64::consts::PI,
            "must be in [0, π] rad (hard: 0.1745, 10°)",
        ),
    ] {
        check(
            value.is_finite() && (0.0..=bound).contains(&value),
            field,
            value,
            rule,
        )?;
    }
    Ok(())
}
