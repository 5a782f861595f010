//! The settings of the scenario families (`[randomization]`): plain data and their bounds. What
//! they do is in `env/src/scenario/` (the draws, the perception, the nudge).

use fairgrasp_kinematics::Pose;
use serde::{Deserialize, Serialize};

use crate::config::range::Range;

/// A camera extrinsic that is off by a fixed rigid transform (the same for every episode of the
/// cell). The observed position of a point `p` (table frame) is
/// `origin + Rz(yaw)·(p − origin) + xyz`, and the observed yaw is the true yaw `+ yaw`: the cell
/// seen through a camera turned by `yaw` about the vertical through `origin` and shifted by
/// `xyz`. The physics is unaffected.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraOffset {
    /// Point on the table the error turns about (where the camera looks), table frame x, y \[m\].
    pub origin: [f64; 2],
    /// Translation error, table frame \[m\] (each component at most [`MAX_CAMERA_SHIFT`]).
    pub xyz: [f64; 3],
    /// Yaw error about the world vertical \[rad\] (at most [`MAX_CAMERA_YAW`] either way).
    pub yaw: f64,
}

/// Largest accepted translation error per axis \[m\].
pub const MAX_CAMERA_SHIFT: f64 = 0.05;
/// Largest accepted yaw error \[rad\] (15°).
pub const MAX_CAMERA_YAW: f64 = 15.0 * std::f64::consts::PI / 180.0;

impl CameraOffset {
    /// The error as a transform of the table frame: `T(origin + xyz) · Rz(yaw) · T(−origin)`.
    pub fn in_table(&self) -> Pose {
        let [ox, oy] = self.origin;
        let to_origin = Pose::from_xyz_rpy([-ox, -oy, 0.0], [0.0; 3]);
        let turn = Pose::from_xyz_rpy([0.0; 3], [0.0, 0.0, self.yaw]);
        let back = Pose::from_xyz_rpy([ox + self.xyz[0], oy + self.xyz[1], self.xyz[2]], [0.0; 3]);
        back.compose(&turn).compose(&to_origin)
    }
}

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
/// Smallest accepted `min_tcp_distance` \[m\].
pub const MIN_TCP_DISTANCE: f64 = 0.12;
