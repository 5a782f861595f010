//! What the six-axis wrist sensor tells at the first touch of a place cycle, before any control
//! uses it (`fairgrasp wrench-probe`): on each scenario the force search runs until, searching
//! (after the grasp and the carry), the wrist first feels the touch force; there the reading is compared with the truth:
//!
//! - **the wall**: a cube whose bottom is more than 1 mm above the pocket's floor rests on the
//!   rim: on the wall its centre is off towards (in the fixture's true frame, by the larger
//!   component), and on every wall its bottom reaches over (two, when it is off on both axes by
//!   more than the clearance); the reading names a wall too: its centre of pressure on the rim's plane
//!   ([`Wrench::centre_of_pressure`]), in the frame of the pocket *as the cell knows it*, by its
//!   larger component. A cell can only use what it knows: the observed pocket, the joints (the
//!   flange by FK) and the sensor.
//! - **the tilt's sign** (the cube turned in the grip, `place_tilted`'s error): a cube turned by
//!   +θ about the TCP's x (the axis between the pads) hangs with its +y side (the TCP's) low.
//!   Over the pocket that low side dips into the opening (the tilted cube is up to 8 mm wider
//!   than the cube, the opening 4 mm), and the *high* side's bottom edge meets the rim first: the
//!   reading's centre of pressure along the TCP's y, which the torque about the pads' axis
//!   carries, has the sign opposite to the turn's. (The probe was first written expecting the
//!   low side to touch; its first run read the opposite sign on every tilted scenario, which is
//!   how the dipping was found: docs/place.md.)

use fairgrasp_env::TaskEnv;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::scenario::error_mix::ErrorFamily;
use fairgrasp_env::sensor::Wrench;
use fairgrasp_env::{EnvConfig, EnvError, Observation};
use fairgrasp_kinematics::Pose;
use fairgrasp_planner::ScriptedPlace;
use fairgrasp_planner::place::script::PlacePhase;
use serde::Serialize;

/// A wall of the square pocket, in the fixture's frame: the one at +x, −x, +y or −y; or the
/// floor (the cube touched inside the opening).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Wall {
    PlusX,
    MinusX,
    PlusY,
    MinusY,
    Floor,
}

impl Wall {
    /// The wall a direction `(x, y)` of the fixture's frame points at (its larger component).
    pub fn named_by(x: f64, y: f64) -> Wall {
        match (x.abs() >= y.abs(), x >= 0.0, y >= 0.0) {
            (true, true, _) => Wall::PlusX,
            (true, false, _) => Wall::MinusX,
            (false, _, true) => Wall::PlusY,
            (false, _, false) => Wall::MinusY,
        }
    }
}

/// One scenario's first touch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TouchRow {
    pub seed: u64,
    /// The scenario's family in a mix (`fixture_error`, `grasp_error`, `tilted`), if any.
    pub family: Option<ErrorFamily>,
    /// The env step of the first touch; `None`: the wrist never felt the touch force.
    pub step: Option<usize>,
    /// Where the cube truly touched: the wall its centre is off towards, or the floor.
    pub true_wall: Option<Wall>,
    /// Every wall the cube's bottom reaches over (a cube off on both axes rests on two).
    pub rim_walls: Vec<Wall>,
    /// The wall the reading names.
    pub read_wall: Option<Wall>,
    /// The reading's centre of pressure on the rim's plane in the observed pocket's frame \[m\].
    pub cop_pocket: Option<[f64; 2]>,
    /// The cube's centre in the true pocket's frame at the touch \[m\].
    pub cube_in_pocket: Option<[f64; 3]>,
    /// The cube's turn in the grip \[rad\] (0: none).
    pub grip_tilt: f64,
    /// The centre of pressure along the TCP's y \[m\] (its sign is the tilt's read).
    pub cop_tcp_y: Option<f64>,
    /// The reading at the touch, `base_link` (torque about the flange).
    pub force: Option<[f64; 3]>,
    pub torque: Option<[f64; 3]>,
}

impl TouchRow {
    /// Touched a wall (the rim), not the floor.
    pub fn on_rim(&self) -> bool {
        self.true_wall.is_some_and(|w| w != Wall::Floor)
    }

    /// The reading named the wall the cube's centre is off towards.
    pub fn wall_read_right(&self) -> bool {
        self.on_rim() && self.read_wall == self.true_wall
    }

    /// The reading named one of the walls the cube rests on.
    pub fn a_rim_wall_read(&self) -> bool {
        self.on_rim() && self.read_wall.is_some_and(|w| self.rim_walls.contains(&w))
    }

    /// A turned cube whose turn's sign the reading gave right (`None`: no turn or no touch):
    /// the high side touches, so the centre of pressure along the TCP's y has the opposite sign
    /// ([`tilt_sign_read`]).
    pub fn tilt_sign_read_right(&self) -> Option<bool> {
        let read = tilt_sign_read(self.cop_tcp_y?);
        (self.grip_tilt != 0.0).then(|| read == self.grip_tilt.signum())
    }
}

/// The sign of the cube's turn in the grip (about the TCP's x) that a first touch on the rim
/// with its centre of pressure `cop_tcp_y` \[m\] along the TCP's y says: the high side touches
/// first (the module's comment), so the opposite sign.
pub fn tilt_sign_read(cop_tcp_y: f64) -> f64 {
    -cop_tcp_y.signum()
}

/// The first touch of the force search (`[task.place.search]`) on the scenarios `seed ..
/// seed + episodes` of `config` (a place preset with the wrist sensor).
pub fn first_touches(
    config: &EnvConfig,
    seed: u64,
    episodes: usize,
    mut progress: impl FnMut(usize),
) -> Result<Vec<TouchRow>, EnvError> {
    let mut env = TaskEnv::new(config.clone())?;
    let mut rows = Vec::with_capacity(episodes);
    for k in 0..episodes {
        rows.push(first_touch(&mut env, config, seed + k as u64)?);
        progress(k + 1);
    }
    Ok(rows)
}

/// One scenario's first touch.
fn first_touch(env: &mut TaskEnv, config: &EnvConfig, seed: u64) -> Result<TouchRow, EnvError> {
    let search = config.task.place.search;
    let mut control = ScriptedPlace::with_search(config, search);
    let (mut obs, _) = env.reset(seed)?;
    control.reset(seed);
    let scenario = env.scenario().cloned();
    let drawn = scenario.as_ref().and_then(|s| s.fixture);
    let mut row = TouchRow {
        seed,
        family: drawn.and_then(|f| f.error_family),
        step: None,
        true_wall: None,
        rim_walls: Vec::new(),
        read_wall: None,
        cop_pocket: None,
        cube_in_pocket: None,
        grip_tilt: drawn.map_or(0.0, |f| f.grip_tilt),
        cop_tcp_y: None,
        force: None,
        torque: None,
    };
    for step in 0..config.task.max_steps {
        let action = control.act(&obs);
        let next = env.step(&action)?;
        obs = next.obs;
        let Some(wrench) = obs.wrist_wrench() else {
            return Ok(row);
        };
        let searching = control.place_phase() == PlacePhase::Search;
        if searching && wrench.force[2] >= search.contact_force {
            row.step = Some(step);
            row.force = Some(wrench.force);
            row.torque = Some(wrench.torque);
            (row.true_wall, row.rim_walls) = truth(env, config).unwrap_or_default();
            read(&mut row, env, config, &obs, &wrench);
            return Ok(row);
        }
        if next.terminated || next.truncated {
            break;
        }
    }
    Ok(row)
}

/// Where the cube truly rests: on the rim when its lowest point is more than 1 mm above the
/// pocket's floor — on the wall its centre is off towards (the fixture's true frame, the larger
/// component), and over every wall its bottom corners reach past the opening; else on the floor.
fn truth(env: &TaskEnv, config: &EnvConfig) -> Option<(Option<Wall>, Vec<Wall>)> {
    let fixture = env.fixture_in_base()?.inverse();
    let cube = env.object_in_base();
    let half = 0.5 * config.scene.cube_size;
    let mut corners: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let c = [0, 1, 2].map(|i| if k >> i & 1 == 0 { -half } else { half });
            fixture.transform_point(cube.transform_point(c))
        })
        .collect();
    corners.sort_by(|a, b| a[2].total_cmp(&b[2]));
    if corners[0][2] <= 0.001 {
        return Some((Some(Wall::Floor), Vec::new()));
    }
    let opening = half + config.task.place.clearance;
    let bottom = &corners[..4];
    let reach = |axis: usize, sign: f64| bottom.iter().any(|c| sign * c[axis] > opening);
    let walls = [
        (Wall::PlusX, 0, 1.0),
        (Wall::MinusX, 0, -1.0),
        (Wall::PlusY, 1, 1.0),
        (Wall::MinusY, 1, -1.0),
    ]
    .into_iter()
    .filter(|&(_, axis, sign)| reach(axis, sign))
    .map(|(w, _, _)| w)
    .collect();
    let centre = fixture.transform_point(cube.xyz());
    Some((Some(Wall::named_by(centre[0], centre[1])), walls))
}

/// What the reading names: the wall its centre of pressure on the rim's plane lies towards, in
/// the observed pocket's frame, and the centre of pressure along the TCP's y.
fn read(row: &mut TouchRow, env: &TaskEnv, config: &EnvConfig, obs: &Observation, w: &Wrench) {
    let Some(pocket) = obs.fixture else {
        return;
    };
    let flange = env.model().fk_flange(&obs.joints);
    let rim = pocket.position[2] + config.task.place.wall_height;
    let Some([x, y]) = w.centre_of_pressure(flange.xyz()[2] - rim, 0.5) else {
        return;
    };
    let at = [flange.xyz()[0] + x, flange.xyz()[1] + y, rim];
    let observed = Pose::from_xyz_rpy(pocket.position, [0.0, 0.0, pocket.yaw]);
    let local = observed.inverse().transform_point(at);
    row.read_wall = Some(Wall::named_by(local[0], local[1]));
    row.cop_pocket = Some([local[0], local[1]]);
    row.cube_in_pocket = env
        .fixture_in_base()
        .map(|f| f.inverse().transform_point(env.object_in_base().xyz()));
    let tcp = env.model().fk_tcp(&obs.joints);
    let rel = [at[0] - tcp.xyz()[0], at[1] - tcp.xyz()[1], 0.0];
    row.cop_tcp_y = Some(tcp.inverse().transform_vector(rel)[1]);
}
