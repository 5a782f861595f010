//! The observation and action spaces, published: names, units and finite bounds per entry, so
//! that a learner (or gymnasium, from Python) never has to guess a layout or a scale.

use fairgrasp_kinematics::ArmModel;
use serde::Serialize;

use crate::config::{ActionSpace, EnvConfig};
use crate::env::obs::{OBS_DIM, OBS_NAMES};

/// Number of values in an action.
pub const ACT_DIM: usize = 7;

/// Names of the action's entries, in order.
pub const ACT_NAMES: [&str; ACT_DIM] = [
    "j1_velocity",
    "j2_velocity",
    "j3_velocity",
    "j4_velocity",
    "j5_velocity",
    "j6_velocity",
    "gripper",
];

/// A box space: per entry a name, a unit and closed bounds `[low, high]`, all finite.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BoxSpace {
    pub names: Vec<&'static str>,
    pub units: Vec<&'static str>,
    pub low: Vec<f64>,
    pub high: Vec<f64>,
}

impl BoxSpace {
    /// Number of entries.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether the space has no entries.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The first entry of `values` outside its bounds (index, value), if any.
    pub fn first_outside(&self, values: &[f64]) -> Option<(usize, f64)> {
        values
            .iter()
            .enumerate()
            .find(|(i, v)| !(self.low[*i]..=self.high[*i]).contains(*v))
            .map(|(i, v)| (i, *v))
    }
}

/// The action space: 6 joint-velocity commands and the gripper command, each in [-1, 1]
/// (joints move at `action · arm.action_scale` rad/s; the gripper −1 open … +1 closed).
pub fn action_space() -> BoxSpace {
    action_space_of(ActionSpace::Joint)
}

/// Names of a task-space action's entries (`arm.action_space = "tcp"`), in order.
pub const TCP_ACT_NAMES: [&str; ACT_DIM] = [
    "tcp_vx",
    "tcp_vy",
    "tcp_vz",
    "tcp_yaw_rate",
    "unused_4",
    "unused_5",
    "gripper",
];

/// The action space of `kind`: every entry in [-1, 1], named, with its unit.
pub fn action_space_of(kind: ActionSpace) -> BoxSpace {
    let (names, units) = match kind {
        ActionSpace::Joint => (ACT_NAMES, ["action_scale·rad/s"; 6]),
        ActionSpace::Tcp => (
            TCP_ACT_NAMES,
            [
                "tcp_speed·m/s",
                "tcp_speed·m/s",
                "tcp_speed·m/s",
                "tcp_yaw_rate·rad/s",
                "unused",
                "unused",
            ],
        ),
    };
    BoxSpace {
        names: names.to_vec(),
        units: units.into_iter().chain(["open(-1)…closed(+1)"]).collect(),
        low: vec![-1.0; ACT_DIM],
        high: vec![1.0; ACT_DIM],
    }
}

/// `[lo, hi]` widened to the nearest `f32` values outside it, so that the `f32` flat view of a
/// value inside the bounds is inside them too.
pub fn f32_outward(lo: f64, hi: f64) -> (f64, f64) {
    let (mut l, mut h) = (lo as f32, hi as f32);
    if f64::from(l) > lo {
        l = l.next_down();
    }
    if f64::from(h) < hi {
        h = h.next_up();
    }
    (f64::from(l), f64::from(h))
}

/// The observation space of an env with `config` and arm `model`, in the order of
/// [`OBS_NAMES`]. The bounds are ones the env guarantees (rounded outward to `f32`, the flat
/// view's type):
/// - joints within the soft limits (the rate limiter stops at them);
/// - joint velocities within twice the FR3 velocity limits (the servo arm stays within the
///   limits themselves; the multibody arm's PD motors may overshoot briefly);
/// - object − TCP within the table's half diagonal plus the arm's reach plus 1 m on each axis
///   (an object that leaves the table ends the episode);
/// - the TCP within the arm's reach plus 0.25 m of the base origin on each axis;
/// - the gripper opening within 2 mm of closed (0) … fully open (the solver keeps the finger
///   joint limits to within a fraction of that); yaw features and pad contacts in
///   [−1, 1] and {0, 1}.
pub fn observation_space(config: &EnvConfig, model: &ArmModel) -> BoxSpace {
    let reach = model.reach() + model.gripper.tcp_offset;
    let table = config.scene.table_size;
    let rel = 0.5 * table[0].hypot(table[1]) + reach + 1.0;
    let tcp = reach + 0.25;
    let mut low = Vec::with_capacity(OBS_DIM);
    let mut high = Vec::with_capacity(OBS_DIM);
    let mut units = Vec::with_capacity(OBS_DIM);
    let mut push = |lo: f64, hi: f64, unit: &'static str| {
        let (lo, hi) = f32_outward(lo, hi);
        low.push(lo);
        high.push(hi);
        units.push(unit);
    };
    for j in &model.joints {
        push(j.lower, j.upper, "rad");
    }
    for j in &model.joints {
        push(-2.0 * j.max_velocity, 2.0 * j.max_velocity, "rad/s");
    }
    for _ in 0..3 {
        push(-rel, rel, "m");
    }
    push(-0.002, model.gripper.opening(0.0) + 0.002, "m");
    for _ in 0..2 {
        push(-1.0, 1.0, "1");
    }
    for _ in 0..3 {
        push(-tcp, tcp, "m");
    }
    for _ in 0..2 {
        push(0.0, 1.0, "bool");
    }
    BoxSpace {
        names: OBS_NAMES.to_vec(),
        units,
        low,
        high,
    }
}
