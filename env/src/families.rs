//! Scenario families: imperfections of a real cell that an open-loop script does not handle.
//!
//! - a **miscalibrated camera** ([`CameraOffset`]): the camera's extrinsic calibration to the
//!   base is off by a fixed rigid error for the cell, so every observed cube pose is the true one
//!   moved by that error (applied in [`crate::perception::observe_object`]);
//! - a **nudged cube** ([`NudgeConfig`], drawn per scenario as a [`Nudge`]): the cube is pushed
//!   across the table once, during the approach (carried out by [`crate::nudge::NudgeHook`]).
//!
//! Both are set in `[randomization]` and are off by default. Frames: the table frame
//! ([`crate::Mount`]: on the table top under the base, z up, x along the base's heading).

use std::f64::consts::TAU;

use fairgrasp_kinematics::{ArmModel, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::config::{EnvConfig, Range};
use crate::mount::Mount;
use crate::randomize::top_down_grasp;

/// A camera extrinsic that is off by a fixed rigid transform (the same for every episode of the
/// cell). The observed position of a point `p` (table frame) is
/// `origin + Rz(yaw)·(p − origin) + xyz`, and the observed yaw is the true yaw `+ yaw`: the cell
/// seen through a camera turned by `yaw` about the vertical through `origin` and shifted by
/// `xyz`. The physics is unaffected.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraOffset {
    /// Point on the table the error turns about (where the camera looks), table frame x, y [m].
    pub origin: [f64; 2],
    /// Translation error, table frame [m] (each component at most [`MAX_CAMERA_SHIFT`]).
    pub xyz: [f64; 3],
    /// Yaw error about the world vertical [rad] (at most [`MAX_CAMERA_YAW`] either way).
    pub yaw: f64,
}

/// Largest accepted translation error per axis [m].
pub const MAX_CAMERA_SHIFT: f64 = 0.05;
/// Largest accepted yaw error [rad] (15°).
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
    /// Push length on the table [m], drawn uniformly (0 < min ≤ max ≤ [`MAX_NUDGE`]).
    pub distance: Range,
    /// Env step (0-based, before that step's action) at which the push happens, drawn
    /// uniformly in `[min, max]`.
    pub step: [usize; 2],
    /// The push is skipped unless the TCP is at least this far from the cube centre [m], before
    /// and after it (≥ [`MIN_TCP_DISTANCE`]: 5 cm of gap plus the cube's half-diagonal and the
    /// open fingers' reach).
    pub min_tcp_distance: f64,
}

/// Longest accepted push [m].
pub const MAX_NUDGE: f64 = 0.15;

/// A wrist camera (`[randomization] wrist_camera = { range }`): once the TCP is within `range`
/// [m] of the cube's centre, the observation also carries the cube's pose as the wrist camera
/// sees it, exactly ([`crate::Observation::wrist_camera`]); farther away, nothing. The fixed
/// camera's view (the observation's cube) keeps its error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WristCamera {
    pub range: f64,
}

/// The longest wrist-camera range accepted [m].
pub const MAX_WRIST_RANGE: f64 = 0.5;
/// Smallest accepted `min_tcp_distance` [m].
pub const MIN_TCP_DISTANCE: f64 = 0.12;

/// One scenario's push: at env step `step`, the cube is moved by `offset_xy` (table frame) [m],
/// keeping its height and yaw, at rest, unless the TCP is nearer than `min_tcp_distance` [m]
/// to the cube centre before or after the push (then it is skipped).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Nudge {
    pub step: usize,
    pub offset_xy: [f64; 2],
    pub min_tcp_distance: f64,
}

/// Pushes tried before a scenario is given no push (each must leave a graspable cube).
const NUDGE_DRAWS: usize = 100;

/// Draws the push for the scenario `seed` whose cube rests at `object_xy`, `object_yaw` (table
/// frame): uniform direction, length and step, redrawn until the pushed cube stays in the
/// sector's radius and admits a top-down grasp from `start_joints`. Its own generator (the seed
/// mixed with a constant), so the rest of the scenario is the one the family's base preset draws.
#[allow(clippy::too_many_arguments)]
pub fn draw_nudge(
    nudge: &NudgeConfig,
    config: &EnvConfig,
    model: &ArmModel,
    mount: &Mount,
    seed: u64,
    object_xy: [f64; 2],
    object_yaw: f64,
    start_joints: &[f64; 6],
) -> Option<Nudge> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6e75_6467_655f_7631);
    let radius = config.randomization.radius;
    for _ in 0..NUDGE_DRAWS {
        let direction = rng.random_range(0.0..TAU);
        let length = rng.random_range(nudge.distance[0]..=nudge.distance[1]);
        let step = rng.random_range(nudge.step[0]..=nudge.step[1]);
        let offset_xy = [length * direction.cos(), length * direction.sin()];
        let xy = [object_xy[0] + offset_xy[0], object_xy[1] + offset_xy[1]];
        let r = xy[0].hypot(xy[1]);
        if r < radius[0] || r > radius[1] {
            continue;
        }
        let pose = mount.resting_object_in_base(xy, object_yaw, config.scene.cube_size);
        if top_down_grasp(model, mount, &pose, start_joints).is_some() {
            return Some(Nudge {
                step,
                offset_xy,
                min_tcp_distance: nudge.min_tcp_distance,
            });
        }
    }
    None
}
