//! The stack task's settings (`[task.stack]`): where the second cube stands and how well the
//! cell sees it, what counts as stacked, the grasp and the takt, and their rules (`check_stack`,
//! called by `EnvConfig::validate`). Plain data and its checks, in the config layer like the
//! place task's `settings.rs`; the task's rules are in [`crate::task::stack::rules`], the second
//! cube's draw is the fixture's (`env/src/scenario/fixture/`), its body `env/src/sim/fixture.rs`.
//!
//! Frames: the table frame ([`crate::Mount`]: on the table top under the base, z up, x along
//! the base's heading). Units: metres, radians.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check_in};
use crate::config::error::ConfigError;
use crate::config::range::Range;
use crate::scenario::fixture::settings::{
    FixtureBox, FixtureSite, SiteKeys, check_grasp_height, check_site,
};

/// The second cube and the stacked criterion (`[task.stack]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StackConfig {
    /// Draw the second cube's position in `base_radius` × `base_angle` (else `base_xy`).
    pub randomize: bool,
    /// The second cube's centre when not randomised, table frame x, y \[m\].
    pub base_xy: [f64; 2],
    /// Sector its centre is drawn in: distance from under the base origin \[m\] and angle from
    /// the base's heading \[rad\].
    pub base_radius: Range,
    pub base_angle: Range,
    /// Draw its yaw in [0, π/2) (else 0; a cube repeats every 90°).
    pub random_yaw: bool,
    /// Its centre is drawn at least this far from the held cube's start \[m\].
    pub min_distance_from_cube: f64,
    /// How well the cell's camera sees the second cube: a per-episode error on its *observed*
    /// position, table plane \[m\], and yaw \[rad\] (standard deviations; 0 = exact). The
    /// physics is unaffected.
    pub observed_position_noise: f64,
    pub observed_yaw_noise: f64,
    /// Stacked: the held cube's centre at most this far from the second cube's, along each of
    /// its faces \[m\] ("squarely": the default 5 mm is a tenth of the 50 mm cube).
    pub max_offset: f64,
    /// Stacked: the held cube's bottom at most this far above the second cube's top \[m\] (it
    /// rests on it), and standing on a face, tilted at most `max_tilt` \[rad\].
    pub max_gap: f64,
    pub max_tilt: f64,
    /// Clear: the TCP at least this far above the cube's top \[m\], neither pad touching it.
    pub clear_height: f64,
    /// Where the TCP holds the cube: this far above its centre \[m\] (the grasp the stack
    /// scripts plan, so that the pads stay clear of the second cube when the cube lands).
    pub grasp_height: f64,
    /// The cell's takt: the time one cycle may take from the reset \[s\].
    pub takt: f64,
}

impl Default for StackConfig {
    fn default() -> Self {
        Self {
            randomize: false,
            base_xy: [0.30, 0.20],
            base_radius: [0.25, 0.40],
            base_angle: [-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2],
            random_yaw: false,
            min_distance_from_cube: 0.12,
            observed_position_noise: 0.0,
            observed_yaw_noise: 0.0,
            max_offset: 0.005,
            max_gap: 0.002,
            max_tilt: 2f64.to_radians(),
            clear_height: 0.03,
            grasp_height: 0.012,
            takt: 20.0,
        }
    }
}

impl StackConfig {
    /// Where the second cube stands and how the cell sees it; the seat is its top face.
    pub fn site(&self, cube_size: f64) -> FixtureSite {
        FixtureSite {
            randomize: self.randomize,
            xy: self.base_xy,
            radius: self.base_radius,
            angle: self.base_angle,
            random_yaw: self.random_yaw,
            min_distance_from_cube: self.min_distance_from_cube,
            observed_position_noise: self.observed_position_noise,
            observed_yaw_noise: self.observed_yaw_noise,
            seat_height: cube_size,
        }
    }

    /// The second cube as the fixture's one box: as large as the held cube, standing on the
    /// table at the fixture's origin.
    pub fn base_boxes(cube_size: f64) -> Vec<FixtureBox> {
        let h = 0.5 * cube_size;
        vec![([h; 3], [0.0, 0.0, h])]
    }
}

/// Refuses a setting that cannot mean what it says, naming the field.
pub(crate) fn check_stack(s: &StackConfig, cube_size: f64) -> Result<(), ConfigError> {
    for (value, field, high, unit) in [
        (s.max_offset, "task.stack.max_offset", 0.5 * cube_size, "m"),
        (s.max_gap, "task.stack.max_gap", 0.02, "m"),
        (s.max_tilt, "task.stack.max_tilt", 0.5, "rad"),
        (s.clear_height, "task.stack.clear_height", 0.3, "m"),
        (
            s.min_distance_from_cube,
            "task.stack.min_distance_from_cube",
            1.0,
            "m",
        ),
        (s.takt, "task.stack.takt", 3600.0, "s"),
    ] {
        check_in(value, field, Bounds::above_to(0.0, high).unit(unit), "")?;
    }
    check_grasp_height(s.grasp_height, cube_size, "task.stack.grasp_height")?;
    check_site(&s.site(cube_size), &STACK_SITE_KEYS)
}

/// The names of the second cube's site in `[task.stack]`.
pub const STACK_SITE_KEYS: SiteKeys = SiteKeys {
    table: "task.stack",
    xy: ["task.stack.base_xy[0]", "task.stack.base_xy[1]"],
    radius: "task.stack.base_radius",
    angle: "task.stack.base_angle",
    min_distance_from_cube: "task.stack.min_distance_from_cube",
    observed_position_noise: "task.stack.observed_position_noise",
    observed_yaw_noise: "task.stack.observed_yaw_noise",
};
