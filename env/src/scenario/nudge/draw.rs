//! The scenario's push of the cube (the `nudged` family): drawn once per scenario from its seed,
//! with a generator of its own.

use std::f64::consts::TAU;

use fairgrasp_kinematics::ArmModel;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use crate::cell::mount::Mount;
use crate::config::EnvConfig;
use crate::scenario::graspable::top_down_grasp;
use crate::scenario::nudge::settings::NudgeConfig;

/// One scenario's push: at env step `step`, the cube is moved by `offset_xy` (table frame) \[m\],
/// keeping its height and yaw, at rest, unless the TCP is nearer than `min_tcp_distance` \[m\]
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
