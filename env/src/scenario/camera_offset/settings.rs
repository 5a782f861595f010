//! The miscalibrated camera's settings (`[randomization] camera_offset`), plain data, their
//! bounds and rules.

use fairgrasp_kinematics::Pose;
use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check_in};
use crate::config::error::ConfigError;

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

    /// Refuses an error that is not finite or beyond its bounds, naming the field.
    pub fn check(&self) -> Result<(), ConfigError> {
        let origin = Bounds::closed(-2.0, 2.0).unit("m");
        for (v, field) in self.origin.iter().zip([
            "randomization.camera_offset.origin[0]",
            "randomization.camera_offset.origin[1]",
        ]) {
            check_in(*v, field, origin, "(within 2 m of the base)")?;
        }
        let shift = Bounds::closed(-MAX_CAMERA_SHIFT, MAX_CAMERA_SHIFT).unit("m");
        for (v, field) in self.xyz.iter().zip([
            "randomization.camera_offset.xyz[0]",
            "randomization.camera_offset.xyz[1]",
            "randomization.camera_offset.xyz[2]",
        ]) {
            check_in(*v, field, shift, "")?;
        }
        check_in(
            self.yaw,
            "randomization.camera_offset.yaw",
            Bounds::closed(-MAX_CAMERA_YAW, MAX_CAMERA_YAW).unit("rad"),
            "(15°)",
        )
    }
}
