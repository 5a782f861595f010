//! Where the place task's fixture stands in a scenario: drawn from the scenario's seed (its own
//! generator, so the rest of the scenario is the one the lift task draws), checked to be far
//! enough from the cube and reachable top-down with the cube held.

use std::f64::consts::FRAC_PI_2;

use fairgrasp_kinematics::ArmModel;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use crate::cell::mount::Mount;
use crate::config::EnvConfig;
use crate::scenario::graspable::top_down_grasp;
use crate::scenario::grip_tilt::draw::draw_grip_tilt;
use crate::scenario::noise::gauss;

/// The fixture's pose in one scenario: the pocket's centre on the table top, table frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FixturePose {
    /// Centre x, y \[m\].
    pub xy: [f64; 2],
    /// Yaw about the world vertical, relative to the base's heading \[rad\] (the pocket repeats
    /// every 90°).
    pub yaw: f64,
    /// The error on the observed position, table plane x, y \[m\], and yaw \[rad\]
    /// (`task.place.observed_position_noise`, `observed_yaw_noise`).
    pub observed_xy_error: [f64; 2],
    pub observed_yaw_error: f64,
    /// How far the cube turns in the grip once carried, about the axis between the pads \[rad\]
    /// (`task.place.grip_tilt`; 0 = not at all).
    pub grip_tilt: f64,
    /// The fixture's friction coefficient (`task.place.fixture_friction`; `None`: the table's).
    pub friction: Option<f64>,
}

impl FixturePose {
    /// The fixture of a config that draws nothing: at `task.place.fixture_xy`, yaw 0, known
    /// exactly, no grip tilt, the table's friction.
    pub fn fixed(config: &EnvConfig) -> FixturePose {
        FixturePose {
            xy: config.task.place.fixture_xy,
            yaw: 0.0,
            observed_xy_error: [0.0; 2],
            observed_yaw_error: 0.0,
            grip_tilt: 0.0,
            friction: None,
        }
    }
}

/// Fixture poses tried before a scenario is given up.
const FIXTURE_DRAWS: usize = 200;

/// The fixture pose of scenario `seed` whose cube starts at `cube_xy` (table frame): the fixed
/// one, or one drawn in the configured sector; `None` if no draw is at least
/// `min_distance_from_cube` from the cube and admits a top-down placing of the cube from
/// `start_joints`.
pub fn draw_fixture(
    config: &EnvConfig,
    model: &ArmModel,
    mount: &Mount,
    seed: u64,
    cube_xy: [f64; 2],
    start_joints: &[f64; 6],
) -> Option<FixturePose> {
    let p = &config.task.place;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6669_7874_7572_6531);
    let draws = if p.randomize { FIXTURE_DRAWS } else { 1 };
    for _ in 0..draws {
        let xy = if p.randomize {
            let r = rng
                .random_range(p.fixture_radius[0].powi(2)..=p.fixture_radius[1].powi(2))
                .sqrt();
            let a = rng.random_range(p.fixture_angle[0]..=p.fixture_angle[1]);
            [r * a.cos(), r * a.sin()]
        } else {
            p.fixture_xy
        };
        let yaw = if p.random_yaw {
            rng.random_range(0.0..FRAC_PI_2)
        } else {
            0.0
        };
        let observed_xy_error = [
            gauss(&mut rng, p.observed_position_noise),
            gauss(&mut rng, p.observed_position_noise),
        ];
        let observed_yaw_error = gauss(&mut rng, p.observed_yaw_noise);
        let apart = (xy[0] - cube_xy[0]).hypot(xy[1] - cube_xy[1]) >= p.min_distance_from_cube;
        let seated = mount.resting_object_in_base(xy, yaw, config.scene.cube_size);
        if apart && top_down_grasp(model, mount, &seated, start_joints).is_some() {
            let (grip_tilt, friction) = draw_contact_conditions(config, seed);
            return Some(FixturePose {
                xy,
                yaw,
                observed_xy_error,
                observed_yaw_error,
                grip_tilt,
                friction,
            });
        }
    }
    None
}

/// The grip tilt and the fixture's friction of scenario `seed` (`task.place.grip_tilt`,
/// `fixture_friction`), from a generator of their own: the cube's and the fixture's poses are
/// those of the same scenario without them.
fn draw_contact_conditions(config: &EnvConfig, seed: u64) -> (f64, Option<f64>) {
    let p = &config.task.place;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6772_6970_5f74_696c);
    let grip_tilt = draw_grip_tilt(&mut rng, p.grip_tilt);
    let friction = p.fixture_friction.map(|[lo, hi]| rng.random_range(lo..=hi));
    (grip_tilt, friction)
}
