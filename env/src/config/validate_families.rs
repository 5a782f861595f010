//! Checking the scenario families' fields of an [`EnvConfig`] ([`crate::scenario::families`]):
//! the wrist camera, the camera offset, the push. Called by [`EnvConfig::validate`].

use crate::config::check::{check, check_range};
use crate::config::env_config::EnvConfig;
use crate::config::error::ConfigError;

impl EnvConfig {
    /// The scenario families' fields ([`crate::scenario::families`]).
    pub(crate) fn validate_families(&self) -> Result<(), ConfigError> {
        use crate::config::families::{
            MAX_CAMERA_SHIFT, MAX_CAMERA_YAW, MAX_NUDGE, MAX_WRIST_RANGE, MIN_TCP_DISTANCE,
        };
        let r = &self.randomization;
        if let Some(w) = &r.wrist_camera {
            check(
                w.range.is_finite() && w.range > 0.0 && w.range <= MAX_WRIST_RANGE,
                "randomization.wrist_camera.range",
                w.range,
                "must be in (0, 0.5] m",
            )?;
        }
        if let Some(c) = &r.camera_offset {
            check(
                c.origin.iter().all(|v| v.is_finite() && v.abs() <= 2.0),
                "randomization.camera_offset.origin",
                c.origin,
                "must be finite and within 2 m of the base [m]",
            )?;
            check(
                c.xyz
                    .iter()
                    .all(|v| v.is_finite() && v.abs() <= MAX_CAMERA_SHIFT),
                "randomization.camera_offset.xyz",
                c.xyz,
                "each component must be finite and within ±0.05 m",
            )?;
            check(
                c.yaw.is_finite() && c.yaw.abs() <= MAX_CAMERA_YAW,
                "randomization.camera_offset.yaw",
                c.yaw,
                "must be finite and within ±0.2618 rad (15°)",
            )?;
        }
        if let Some(n) = &r.nudge {
            check_range(&n.distance, "randomization.nudge.distance", 0.0)?;
            check(
                n.distance[0] > 0.0 && n.distance[1] <= MAX_NUDGE,
                "randomization.nudge.distance",
                n.distance,
                "must lie in (0, 0.15] m",
            )?;
            check(
                n.step[0] <= n.step[1] && n.step[1] < self.task.max_steps,
                "randomization.nudge.step",
                n.step,
                "min must not exceed max, and max must be below task.max_steps",
            )?;
            check(
                n.min_tcp_distance.is_finite() && n.min_tcp_distance >= MIN_TCP_DISTANCE,
                "randomization.nudge.min_tcp_distance",
                n.min_tcp_distance,
                "must be at least 0.12 m (5 cm of gap plus the cube and the open fingers)",
            )?;
            check(
                r.position,
                "randomization.nudge",
                "set",
                "needs randomization.position = true (the push stays in its radius range)",
            )?;
        }
        Ok(())
    }
}
