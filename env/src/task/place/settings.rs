//! The place task's settings (`[task.place]`): the fixture, where it stands, what counts as
//! seated, and their rules (`check_place`, called by `EnvConfig::validate`). Plain data and
//! its checks, in the config layer like a scenario family's `settings.rs`; the task's rules
//! are in [`crate::task::place::rules`], the fixture's draw in `env/src/scenario/fixture/`,
//! its bodies in `env/src/sim/fixture.rs`.
//!
//! Frames: the table frame ([`crate::Mount`]: on the table top under the base, z up, x along
//! the base's heading). Units: metres, radians.

use serde::{Deserialize, Serialize};

use crate::config::check::{check, check_range};
use crate::config::error::ConfigError;
use crate::config::range::Range;
use crate::scenario::grip_tilt::settings::check_grip_tilt;

/// The fixture and the seated criterion (`[task.place]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PlaceConfig {
    /// Gap between the cube and each wall of the square pocket \[m\] (the pocket's side is the
    /// cube's edge plus twice this).
    pub clearance: f64,
    /// Height of the pocket's walls above the table top \[m\]; the pocket's floor is the table.
    pub wall_height: f64,
    /// Thickness of each wall \[m\].
    pub wall_thickness: f64,
    /// Draw the fixture's position in `fixture_radius` × `fixture_angle` (else `fixture_xy`).
    pub randomize: bool,
    /// The fixture's centre when not randomised, table frame x, y \[m\].
    pub fixture_xy: [f64; 2],
    /// Sector the fixture's centre is drawn in: distance from under the base origin \[m\] and
    /// angle from the base's heading \[rad\].
    pub fixture_radius: Range,
    pub fixture_angle: Range,
    /// Draw the fixture's yaw in [0, π/2) (else 0; the pocket repeats every 90°).
    pub random_yaw: bool,
    /// The fixture's centre is drawn at least this far from the cube's start \[m\].
    pub min_distance_from_cube: f64,
    /// Seated: the cube's bottom at most this far above the table top \[m\] and tilted at most
    /// `max_tilt` \[rad\]: standing on a face. A cube wedged across a pocket with 2 mm of
    /// clearance leans up to ~4.6°, so the default 2° tells it from a seated one.
    pub seated_height: f64,
    pub max_tilt: f64,
    /// Clear: the TCP at least this far above the cube's top \[m\], neither pad touching it.
    pub clear_height: f64,
    /// Where the TCP holds the cube: this far above its centre \[m\] (the grasp the place script
    /// plans, so that the cube stands out below the pads and the pads pass over the walls).
    pub grasp_height: f64,
    /// How well the cell knows where the fixture is (its layout's tolerance, or a second
    /// camera): a per-episode error on the *observed* fixture's position, table plane \[m\], and
    /// yaw \[rad\] (standard deviations; 0 = exact). The physics is unaffected; the cube's own
    /// camera errors (`[randomization]`) do not apply to the fixture.
    pub observed_position_noise: f64,
    pub observed_yaw_noise: f64,
    /// The grasp's unobserved tilt: once per episode, when the cube is first carried
    /// [`GRIP_TILT_LIFT`](crate::scenario::grip_tilt::GRIP_TILT_LIFT) above the table, it turns
    /// in the grip about the axis between the pads (the TCP's x) by an angle drawn uniformly in
    /// this range, with a random sign \[rad\] (`[0, 0]`: never; the `grip_tilt` family,
    /// `env/src/scenario/grip_tilt/`). What a grasp above or beside the cube's centre of mass, or a knock
    /// during the lift, does on a real cell; nothing observes it.
    pub grip_tilt: Range,
    /// The friction coefficient between the fixture's walls and what touches them, drawn per
    /// episode uniformly in this range (`None`: the table's, `scene.table_friction`).
    pub fixture_friction: Option<Range>,
    /// The force-guided search's settings as the cell's integrator tuned them for this family
    /// (`[task.place.search]`; `planner::SearchParams::tuned_for` reads them).
    pub search: SearchTuning,
}

/// The tuned parameters of the force-guided search (`[task.place.search]`): what an integrator
/// sets per cell after a tuning run (`scripts/tune-force-search.sh`, docs/place.md). The
/// defaults were tuned on `place_grasp_error` and `place_fixture_error`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SearchTuning {
    /// Upward wrist force that counts as a touch \[N\].
    pub contact_force: f64,
    /// The spiral's pitch: its radius grows this much per turn \[m\].
    pub pitch: f64,
    /// The spiral's speed along its path \[m/s\].
    pub speed: f64,
    /// A touch within this height above the pocket's floor counts as the cube on the floor;
    /// a higher one is the rim \[m\] (`None`: half the wall).
    pub floor_band: Option<f64>,
}

impl Default for SearchTuning {
    fn default() -> Self {
        Self {
            contact_force: 1.5,
            pitch: 0.003,
            speed: 0.01,
            floor_band: None,
        }
    }
}

impl Default for PlaceConfig {
    fn default() -> Self {
        Self {
            clearance: 0.002,
            wall_height: 0.010,
            wall_thickness: 0.010,
            randomize: false,
            fixture_xy: [0.30, 0.20],
            fixture_radius: [0.25, 0.40],
            fixture_angle: [-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2],
            random_yaw: false,
            min_distance_from_cube: 0.12,
            seated_height: 0.002,
            max_tilt: 2f64.to_radians(),
            clear_height: 0.03,
            grasp_height: 0.012,
            observed_position_noise: 0.0,
            observed_yaw_noise: 0.0,
            grip_tilt: [0.0, 0.0],
            fixture_friction: None,
            search: SearchTuning::default(),
        }
    }
}

impl PlaceConfig {
    /// The pocket's inner half side for a cube of edge `cube_size` \[m\].
    pub fn pocket_half_side(&self, cube_size: f64) -> f64 {
        0.5 * cube_size + self.clearance
    }
}

/// Refuses a fixture or criterion that cannot mean what it says, naming the field.
pub(crate) fn check_place(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    check_fixture(p, cube_size)?;
    check_observation_noise(p)?;
    check_contact_conditions(p)?;
    check_search(p)
}

/// The pocket's sizes, the seated and clear criteria, the grasp, where the fixture stands.
fn check_fixture(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    for (value, field, lo, hi, rule) in [
        (
            p.clearance,
            "task.place.clearance",
            0.0,
            0.02,
            "must be in (0, 0.02] m",
        ),
        (
            p.wall_height,
            "task.place.wall_height",
            0.0,
            0.05,
            "must be in (0, 0.05] m",
        ),
        (
            p.wall_thickness,
            "task.place.wall_thickness",
            0.0,
            0.05,
            "must be in (0, 0.05] m",
        ),
        (
            p.seated_height,
            "task.place.seated_height",
            0.0,
            0.02,
            "must be in (0, 0.02] m",
        ),
        (
            p.max_tilt,
            "task.place.max_tilt",
            0.0,
            0.5,
            "must be in (0, 0.5] rad",
        ),
        (
            p.clear_height,
            "task.place.clear_height",
            0.0,
            0.3,
            "must be in (0, 0.3] m",
        ),
        (
            p.min_distance_from_cube,
            "task.place.min_distance_from_cube",
            0.0,
            1.0,
            "must be in (0, 1] m",
        ),
    ] {
        check(value > lo && value <= hi, field, value, rule)?;
    }
    check(
        p.grasp_height.abs() < 0.5 * cube_size,
        "task.place.grasp_height",
        p.grasp_height,
        "must hold the cube: less than half its edge above or below its centre",
    )?;
    check(
        p.fixture_xy.iter().all(|v| v.abs() <= 2.0),
        "task.place.fixture_xy",
        p.fixture_xy,
        "must be within 2 m of the base [m]",
    )?;
    check_range(&p.fixture_radius, "task.place.fixture_radius", 0.0)?;
    check_range(
        &p.fixture_angle,
        "task.place.fixture_angle",
        -std::f64::consts::PI,
    )
}

/// How well the cell knows the fixture's pose.
fn check_observation_noise(p: &PlaceConfig) -> Result<(), ConfigError> {
    check(
        (0.0..=0.05).contains(&p.observed_position_noise),
        "task.place.observed_position_noise",
        p.observed_position_noise,
        "must be in [0, 0.05] m",
    )?;
    check(
        (0.0..=0.5).contains(&p.observed_yaw_noise),
        "task.place.observed_yaw_noise",
        p.observed_yaw_noise,
        "must be in [0, 0.5] rad",
    )
}

/// The grip's tilt and the fixture's friction, drawn per episode.
fn check_contact_conditions(p: &PlaceConfig) -> Result<(), ConfigError> {
    check_grip_tilt(&p.grip_tilt)?;
    if let Some(friction) = &p.fixture_friction {
        check_range(friction, "task.place.fixture_friction", 0.0)?;
        check(
            friction[1] <= 2.0,
            "task.place.fixture_friction",
            friction,
            "must be within [0, 2] (a friction coefficient)",
        )?;
    }
    Ok(())
}

/// The force search's tuned settings (`[task.place.search]`).
fn check_search(p: &PlaceConfig) -> Result<(), ConfigError> {
    let s = &p.search;
    for (value, field, lo, hi, rule) in [
        (
            s.contact_force,
            "task.place.search.contact_force",
            0.1,
            30.0,
            "must be in [0.1, 30] N",
        ),
        (
            s.pitch,
            "task.place.search.pitch",
            0.0005,
            0.02,
            "must be in [0.0005, 0.02] m per turn",
        ),
        (
            s.speed,
            "task.place.search.speed",
            0.001,
            0.1,
            "must be in [0.001, 0.1] m/s",
        ),
    ] {
        check((lo..=hi).contains(&value), field, value, rule)?;
    }
    if let Some(band) = s.floor_band {
        check(
            band > 0.0 && band <= p.wall_height,
            "task.place.search.floor_band",
            band,
            "must be in (0, task.place.wall_height] m",
        )?;
    }
    Ok(())
}
