//! The place task's settings (`[task.place]`): the fixture, where it stands, what counts as
//! seated, and their rules (`check_place`, called by `EnvConfig::validate`). Plain data and
//! its checks, in the config layer like a scenario family's `settings.rs`; the task's rules
//! are in [`crate::task::place::rules`], the fixture's draw in `env/src/scenario/fixture/`,
//! its bodies in `env/src/sim/fixture.rs`.
//!
//! Frames: the table frame ([`crate::Mount`]: on the table top under the base, z up, x along
//! the base's heading). Units: metres, radians.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, RangeBounds, check_in, check_range};
use crate::config::error::ConfigError;
use crate::config::range::Range;
use crate::scenario::error_mix::settings::ErrorMix;
use crate::scenario::fixture::settings::{
    FixtureBox, FixtureSite, SiteKeys, check_grasp_height, check_site,
};
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
    /// The place cell's unlabelled mix (`[task.place.mix]`, `env/src/scenario/error_mix/`):
    /// each scenario keeps the error of one family only, drawn with these weights (`None`:
    /// every error the preset draws, together).
    pub mix: Option<ErrorMix>,
    /// The "search + squaring" control's settings (`[task.place.square]`): the cube pressed
    /// flat on the table beside the pocket before its own search.
    pub square: SquareParams,
    /// The switching search's settings (`[task.place.switch]`): a search per kind of cycle,
    /// chosen from the first touch.
    pub switch: SwitchParams,
    /// The cell's takt: the time one cycle may take from the reset (grasp, carry, seat,
    /// release, clear) \[s\]. A cycle that succeeds later counts as a success but not within
    /// the takt. Default 20 s (240 env steps at 12 Hz), fixed before any control was tuned.
    pub takt: f64,
    /// The force-guided search's settings as the cell's integrator tuned them for this family
    /// (`[task.place.search]`).
    pub search: SearchParams,
}

/// The force-guided search's settings (`[task.place.search]`; `planner::place_search` runs
/// it): what an integrator sets per cell after a tuning run (`fairgrasp tune`, docs/place.md).
/// The defaults of touch force, pitch and speed were tuned on `place_grasp_error` and
/// `place_fixture_error` by a grid; the rest are the search's first settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SearchParams {
    /// Descent speed \[m/s\].
    pub descend_speed: f64,
    /// Upward wrist force that counts as a touch \[N\].
    pub contact_force: f64,
    /// The admittance of the press while spiralling: the TCP's vertical speed per newton of
    /// force below `contact_force` \[m/s/N\] (capped at `descend_speed` either way).
    pub admittance: f64,
    /// The spiral's pitch: its radius grows this much per turn \[m\].
    pub pitch: f64,
    /// The spiral's speed along its path \[m/s\].
    pub speed: f64,
    /// The largest spiral radius searched before giving up (the cube is released where it is)
    /// \[m\].
    pub max_radius: f64,
    /// A touch within this height above the pocket's floor counts as the cube on the floor;
    /// a higher one is the rim \[m\] (`None`: half the wall).
    pub floor_band: Option<f64>,
    /// Check that a found opening leads to the floor: a touch while inserting, above the floor
    /// band, is a false find (the cube tipped off the rim's edge, or caught a corner), and the
    /// spiral goes on from where it was instead of letting the cube go. Off by default (the
    /// search as first tuned); the `place_cell` controls have it on.
    pub check_floor: bool,
}

impl SearchParams {
    /// The defaults, as a constant: a control built on the search's settings (the stack task's
    /// force lower) states only what it changes.
    pub const DEFAULT: SearchParams = SearchParams {
        descend_speed: 0.01,
        contact_force: 1.5,
        admittance: 0.004,
        pitch: 0.003,
        speed: 0.01,
        max_radius: 0.009,
        floor_band: None,
        check_floor: false,
    };
}

impl Default for SearchParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Squaring a cube that hangs tilted in the grip, as an integrator would before a tight
/// insertion (`[task.place.square]`): carry the cube to a spot of free table `offset` beside the
/// pocket (towards where the cube came from), squeeze it with `squeeze` only and lower it at
/// `speed` until it would stand flat on the table, `press` deeper, or until the wrist feels
/// `force`; hold `hold`; squeeze fully again and lift back. Pressed onto the table, a tilted
/// cube turns in the fingers about the pads' axis until a face lies flat. Then the place and its search (`search`, this control's own) as without.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SquareParams {
    /// Distance of the squaring spot from the pocket's observed centre, on the table \[m\].
    pub offset: f64,
    /// Speed down onto the table and back up \[m/s\].
    pub speed: f64,
    /// The press stops when the wrist feels this much upward force \[N\].
    pub force: f64,
    /// How far past "standing flat" the TCP is pressed \[m\] (negative: it stops above).
    pub press: f64,
    /// How long the press is held \[s\].
    pub hold: f64,
    /// The squeeze per finger while pressing and holding \[N\] (the gripper's force setting,
    /// lowered so that the cube can turn between the pads; the full squeeze before the lift).
    pub squeeze: f64,
    /// The search after the squaring.
    pub search: SearchParams,
}

impl Default for SquareParams {
    fn default() -> Self {
        Self {
            offset: 0.08,
            speed: 0.01,
            force: 8.0,
            press: 0.001,
            hold: 0.25,
            squeeze: 1.5,
            search: SearchParams::default(),
        }
    }
}

/// The switching search (`[task.place.switch]`): the search runs `pose`'s settings until its
/// first touch; a touch more than `tilt_band` above or below the rim's height is a cube that
/// hangs tilted (its low corner meets the rim, or dips into the pocket, before its face
/// would), and the search goes on with `tilted`'s settings; else with `pose`'s (a pose error:
/// the face lands flat on the rim). The oracle switch, a ceiling, picks by the family it is
/// told.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SwitchParams {
    /// How far from the rim's height a first touch must be to read as a tilted cube \[m\].
    pub tilt_band: f64,
    /// The search for a cube that hangs square (a fixture or grasp error).
    pub pose: SearchParams,
    /// The search for a cube that hangs tilted.
    pub tilted: SearchParams,
}

impl Default for SwitchParams {
    /// The two settings the first grid found per family (docs/place.md).
    fn default() -> Self {
        Self {
            tilt_band: 0.0015,
            pose: SearchParams::default(),
            tilted: SearchParams {
                contact_force: 1.0,
                pitch: 0.002,
                speed: 0.025,
                floor_band: Some(0.002),
                ..SearchParams::default()
            },
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
            mix: None,
            square: SquareParams::default(),
            switch: SwitchParams::default(),
            takt: 20.0,
            search: SearchParams::default(),
        }
    }
}

impl PlaceConfig {
    /// The pocket's inner half side for a cube of edge `cube_size` \[m\].
    pub fn pocket_half_side(&self, cube_size: f64) -> f64 {
        0.5 * cube_size + self.clearance
    }

    /// Where the fixture stands and how the cell sees it; the seat is the pocket's floor, the
    /// table.
    pub fn site(&self) -> FixtureSite {
        FixtureSite {
            randomize: self.randomize,
            xy: self.fixture_xy,
            radius: self.fixture_radius,
            angle: self.fixture_angle,
            random_yaw: self.random_yaw,
            min_distance_from_cube: self.min_distance_from_cube,
            observed_position_noise: self.observed_position_noise,
            observed_yaw_noise: self.observed_yaw_noise,
            seat_height: 0.0,
        }
    }

    /// The four walls' half extents and centres in the fixture frame \[m\]: two along x (which
    /// also close the corners) and two along y.
    pub fn wall_boxes(&self, cube_size: f64) -> Vec<FixtureBox> {
        let h = self.pocket_half_side(cube_size);
        let (t, z) = (self.wall_thickness, 0.5 * self.wall_height);
        let across = h + 0.5 * t;
        let long = [0.5 * t, h + t, z];
        let short = [h, 0.5 * t, z];
        vec![
            (long, [across, 0.0, z]),
            (long, [-across, 0.0, z]),
            (short, [0.0, across, z]),
            (short, [0.0, -across, z]),
        ]
    }
}

/// Refuses a fixture or criterion that cannot mean what it says, naming the field.
pub(crate) fn check_place(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    check_fixture(p, cube_size)?;
    check_contact_conditions(p)?;
    check_search(p)
}

/// The pocket's sizes, the seated and clear criteria, the grasp, where the fixture stands and
/// how well the cell knows its pose.
fn check_fixture(p: &PlaceConfig, cube_size: f64) -> Result<(), ConfigError> {
    for (value, field, high, unit) in [
        (p.clearance, "task.place.clearance", 0.02, "m"),
        (p.wall_height, "task.place.wall_height", 0.05, "m"),
        (p.wall_thickness, "task.place.wall_thickness", 0.05, "m"),
        (p.seated_height, "task.place.seated_height", 0.02, "m"),
        (p.max_tilt, "task.place.max_tilt", 0.5, "rad"),
        (p.clear_height, "task.place.clear_height", 0.3, "m"),
        (
            p.min_distance_from_cube,
            "task.place.min_distance_from_cube",
            1.0,
            "m",
        ),
        (p.takt, "task.place.takt", 3600.0, "s"),
    ] {
        check_in(value, field, Bounds::above_to(0.0, high).unit(unit), "")?;
    }
    check_grasp_height(p.grasp_height, cube_size, "task.place.grasp_height")?;
    check_site(&p.site(), &PLACE_SITE_KEYS)
}

/// The names of the fixture's site in `[task.place]`.
pub const PLACE_SITE_KEYS: SiteKeys = SiteKeys {
    table: "task.place",
    xy: ["task.place.fixture_xy[0]", "task.place.fixture_xy[1]"],
    radius: "task.place.fixture_radius",
    angle: "task.place.fixture_angle",
    min_distance_from_cube: "task.place.min_distance_from_cube",
    observed_position_noise: "task.place.observed_position_noise",
    observed_yaw_noise: "task.place.observed_yaw_noise",
};

/// The grip's tilt and the fixture's friction, drawn per episode.
fn check_contact_conditions(p: &PlaceConfig) -> Result<(), ConfigError> {
    check_grip_tilt(&p.grip_tilt)?;
    if let Some(friction) = &p.fixture_friction {
        check_range(
            friction,
            "task.place.fixture_friction",
            RangeBounds::new(
                Bounds::closed(0.0, 2.0),
                "(a friction coefficient between the walls and the cube)",
            ),
        )?;
    }
    Ok(())
}

/// Every search's settings: the search's, the squaring's, the switch's two; and the squaring's
/// and the switch's own.
fn check_search(p: &PlaceConfig) -> Result<(), ConfigError> {
    check_one_search(&p.search, "", p.wall_height)?;
    check_one_search(&p.square.search, "task.place.square.search", p.wall_height)?;
    check_one_search(&p.switch.pose, "task.place.switch.pose", p.wall_height)?;
    check_one_search(&p.switch.tilted, "task.place.switch.tilted", p.wall_height)?;
    let q = &p.square;
    for (value, field, low, high, unit) in [
        (q.offset, "task.place.square.offset", 0.05, 0.3, "m"),
        (q.speed, "task.place.square.speed", 0.001, 0.05, "m/s"),
        (q.force, "task.place.square.force", 0.5, 30.0, "N"),
        (q.press, "task.place.square.press", -0.01, 0.01, "m"),
        (q.hold, "task.place.square.hold", 0.0, 3.0, "s"),
        (q.squeeze, "task.place.square.squeeze", 0.2, 100.0, "N"),
        (
            p.switch.tilt_band,
            "task.place.switch.tilt_band",
            0.0001,
            0.01,
            "m",
        ),
    ] {
        check_in(value, field, Bounds::closed(low, high).unit(unit), "")?;
    }
    Ok(())
}

/// One search's settings; `table` names its table in errors (empty: `task.place.search`).
fn check_one_search(s: &SearchParams, table: &str, wall_height: f64) -> Result<(), ConfigError> {
    for b in SEARCH_BOUNDS {
        let value = (b.get)(s);
        let field = match table {
            "" => b.field.to_string(),
            t => b.field.replace("task.place.search", t),
        };
        check_in(value, &field, Bounds::closed(b.lo, b.hi).unit(b.unit), "")?;
    }
    if let Some(band) = s.floor_band {
        let field = match table {
            "" => "task.place.search.floor_band".to_string(),
            t => format!("{t}.floor_band"),
        };
        check_in(
            band,
            &field,
            Bounds::above_to(0.0, wall_height).unit("m"),
            "(up to task.place.wall_height)",
        )?;
    }
    Ok(())
}

/// The bounds of one number of the search's settings.
pub struct SearchBound {
    /// Its key in a preset.
    pub field: &'static str,
    /// Lowest and highest value accepted, in the field's unit.
    pub lo: f64,
    pub hi: f64,
    /// The unit of `lo` and `hi`, as a refusal states it.
    pub unit: &'static str,
    /// Reads it from settings.
    pub get: fn(&SearchParams) -> f64,
}

/// The bounds of the search's numbers (what `fairgrasp tune` may search within, too).
pub const SEARCH_BOUNDS: [SearchBound; 6] = [
    SearchBound {
        field: "task.place.search.descend_speed",
        lo: 0.001,
        hi: 0.05,
        unit: "m/s",
        get: |s| s.descend_speed,
    },
    SearchBound {
        field: "task.place.search.contact_force",
        lo: 0.1,
        hi: 30.0,
        unit: "N",
        get: |s| s.contact_force,
    },
    SearchBound {
        field: "task.place.search.admittance",
        lo: 0.0001,
        hi: 0.05,
        unit: "m/s per N",
        get: |s| s.admittance,
    },
    SearchBound {
        field: "task.place.search.pitch",
        lo: 0.0005,
        hi: 0.02,
        unit: "m per turn",
        get: |s| s.pitch,
    },
    SearchBound {
        field: "task.place.search.speed",
        lo: 0.001,
        hi: 0.1,
        unit: "m/s",
        get: |s| s.speed,
    },
    SearchBound {
        field: "task.place.search.max_radius",
        lo: 0.001,
        hi: 0.05,
        unit: "m",
        get: |s| s.max_radius,
    },
];
