//! `[sensor]`: the cell's sensors beyond the joints and the cameras. Today one: the six-axis
//! wrist force/torque sensor between the flange and the gripper (`[sensor.wrench]`), which every
//! task with a fixture has and the lift task cannot have.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check_in};
use crate::config::error::ConfigError;

/// `[sensor]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct SensorConfig {
    /// The six-axis wrist sensor's noise and resolution; `None`: the defaults
    /// ([`WrenchSensorConfig::default`]) on a task with a fixture, no sensor on the lift task.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wrench: Option<WrenchSensorConfig>,
}

impl SensorConfig {
    /// Nothing set (the section is left out of a written config).
    pub fn is_default(&self) -> bool {
        self.wrench.is_none()
    }
}

/// `[sensor.wrench]`: how the six-axis wrist sensor's reading differs from the true wrench. Per
/// reading and per axis, in the sensor's frame: a Gaussian noise of σ `force_noise` \[N\] and
/// `torque_noise` \[N·m\], then rounding to `force_resolution` \[N\] and `torque_resolution`
/// \[N·m\] (0: none). The defaults are those of a compact industrial six-axis sensor of the size
/// FAIRINO's controller supports (docs/place.md, "The six-axis wrist sensor").
///
/// `friction`: whether the simulated wrench includes the contacts' friction (a real sensor's
/// does), or their normal pushes only — off by default while the shipped controls' settings are
/// those tuned on a reading without it (with it, the tuned force search seats 67 % of
/// `place_fixture_error`'s cycles instead of 96 %: docs/place.md). Turn it on, and tune the
/// controls again, to study the fuller sensor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WrenchSensorConfig {
    pub force_noise: f64,
    pub torque_noise: f64,
    pub force_resolution: f64,
    pub torque_resolution: f64,
    pub friction: bool,
}

impl Default for WrenchSensorConfig {
    fn default() -> Self {
        WrenchSensorConfig {
            force_noise: 0.05,
            torque_noise: 0.002,
            force_resolution: 0.025,
            torque_resolution: 0.0005,
            friction: false,
        }
    }
}

/// The largest noise σ a setting may ask for: a sensor noisier than this reads nothing at the
/// search's touch forces (≈ 1–5 N) and torques (≈ 0.03–0.2 N·m).
const MAX_FORCE_NOISE: f64 = 10.0;
const MAX_TORQUE_NOISE: f64 = 1.0;

impl WrenchSensorConfig {
    /// Each field finite, at least 0 and at most a bound that still reads a touch.
    pub fn check(&self) -> Result<(), ConfigError> {
        let fields = [
            ("force_noise", self.force_noise, MAX_FORCE_NOISE, "N"),
            ("torque_noise", self.torque_noise, MAX_TORQUE_NOISE, "N·m"),
            (
                "force_resolution",
                self.force_resolution,
                MAX_FORCE_NOISE,
                "N",
            ),
            (
                "torque_resolution",
                self.torque_resolution,
                MAX_TORQUE_NOISE,
                "N·m",
            ),
        ];
        for (name, value, max, unit) in fields {
            check_in(
                value,
                &format!("sensor.wrench.{name}"),
                Bounds::closed(0.0, max).unit(unit),
                "(a noisier sensor reads nothing at a touch)",
            )?;
        }
        Ok(())
    }
}
