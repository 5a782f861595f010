//! The wrist camera's settings (`[randomization] wrist_camera`), plain data, and their rule.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check_in};
use crate::config::error::ConfigError;

/// A wrist camera (`[randomization] wrist_camera = { range }`): once the TCP is within `range`
/// \[m\] of the cube's centre, the observation also carries the cube's pose as the wrist camera
/// sees it, exactly ([`crate::Observation::wrist_camera`]); farther away, nothing. The fixed
/// camera's view (the observation's cube) keeps its error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WristCamera {
    pub range: f64,
}

/// The longest wrist-camera range accepted \[m\].
pub const MAX_WRIST_RANGE: f64 = 0.5;

impl WristCamera {
    /// Refuses a range that is not in (0, [`MAX_WRIST_RANGE`]], naming the field.
    pub fn check(&self) -> Result<(), ConfigError> {
        check_in(
            self.range,
            "randomization.wrist_camera.range",
            Bounds::above_to(0.0, MAX_WRIST_RANGE).unit("m"),
            "",
        )
    }
}
