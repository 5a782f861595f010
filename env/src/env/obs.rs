//! The observation: a documented, named layout with a flat `[f32]` view.
//!
//! Positions are in the arm's `base_link` frame \[m\], angles in radians.

use serde::Serialize;

use crate::scenario::perception::ObservedObject;
use crate::sensor::Wrench;

/// Number of values in the flat observation.
pub const OBS_DIM: usize = 23;

/// Names of the flat observation's entries, in order.
pub const OBS_NAMES: [&str; OBS_DIM] = [
    "q1",
    "q2",
    "q3",
    "q4",
    "q5",
    "q6",
    "qd1",
    "qd2",
    "qd3",
    "qd4",
    "qd5",
    "qd6",
    "object_rel_tcp_x",
    "object_rel_tcp_y",
    "object_rel_tcp_z",
    "gripper_opening",
    "object_yaw_sin4",
    "object_yaw_cos4",
    "tcp_x",
    "tcp_y",
    "tcp_z",
    "left_pad_contact",
    "right_pad_contact",
];

/// What the agent sees each step. The first 16 values are the seed recipe's.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Observation {
    /// Joint angles j1 … j6 \[rad\].
    pub joints: [f64; 6],
    /// Joint velocities \[rad/s\], averaged over the last env step.
    pub joint_velocities: [f64; 6],
    /// Object centre minus TCP, in `base_link` \[m\].
    pub object_rel_tcp: [f64; 3],
    /// Distance between the pads' inner faces \[m\] (0.085 fully open).
    pub gripper_opening: f64,
    /// Object yaw about the world vertical, relative to the base's heading (the table frame,
    /// see [`crate::Mount`]) \[rad\]; for a level base, yaw about base z. The cube repeats every
    /// 90°: see `yaw_features`.
    pub object_yaw: f64,
    /// TCP position in `base_link` \[m\].
    pub tcp_position: [f64; 3],
    /// Left and right pads touching the object.
    pub pad_contact: [bool; 2],
    /// The cube as the wrist camera sees it (exactly; `base_link`), when the preset has one and
    /// the TCP is within its range of the cube; otherwise None. Not part of the flat view
    /// ([`OBS_NAMES`]): the task-space residual's features carry it
    /// (`fairgrasp_planner::lift::residual`).
    pub wrist_camera: Option<ObservedObject>,
    /// The place task's fixture as the cell knows it (its pose with the scenario's error,
    /// `task.place.observed_*_noise`; the cube's camera errors do not apply): the pocket's
    /// centre on the table top in `base_link` \[m\] and its yaw; `None` for the lift task. Not
    /// part of the flat view ([`OBS_NAMES`]).
    pub fixture: Option<ObservedObject>,
    /// The force of the six-axis wrist sensor between the flange and the gripper, tared, in
    /// `base_link` \[N\]: the push of the table and the fixture on the gripper and on the cube
    /// while both pads hold it (`crate::sim::contacts::wrist_wrench`), after the step's last
    /// physics substep (only the sensor's noise after a step without physics: nothing touched),
    /// with the sensor's noise (`[sensor.wrench]`); [`Self::wrist_torque`] is its torque.
    /// `None` on a task without a fixture. Not part of the flat view ([`OBS_NAMES`]).
    pub wrist_force: Option<[f64; 3]>,
    /// The six-axis wrist sensor's torque about its origin (the flange, `tool0`), in
    /// `base_link` \[N·m\], tared and with its noise like [`Self::wrist_force`]; `None` where
    /// there is no fixture. Not part of the flat view.
    pub wrist_torque: Option<[f64; 3]>,
}

impl Observation {
    /// `(sin 4·yaw, cos 4·yaw)`: continuous under the cube's 90° symmetry.
    pub fn yaw_features(&self) -> [f64; 2] {
        [(4.0 * self.object_yaw).sin(), (4.0 * self.object_yaw).cos()]
    }

    /// The six-axis wrist sensor's reading in `base_link` (torque about the flange), where the
    /// preset has one.
    pub fn wrist_wrench(&self) -> Option<Wrench> {
        Some(Wrench {
            force: self.wrist_force?,
            torque: self.wrist_torque?,
        })
    }

    /// The object centre in `base_link` \[m\].
    pub fn object_position(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| self.tcp_position[i] + self.object_rel_tcp[i])
    }

    /// Rebuilds an observation from its flat view (the yaw comes back modulo 90°, which is all
    /// a cube's yaw means).
    pub fn from_array(a: &[f32; OBS_DIM]) -> Self {
        let f = |i: usize| a[i] as f64;
        Observation {
            joints: std::array::from_fn(f),
            joint_velocities: std::array::from_fn(|i| f(6 + i)),
            object_rel_tcp: [f(12), f(13), f(14)],
            gripper_opening: f(15),
            object_yaw: f(16).atan2(f(17)) / 4.0,
            tcp_position: [f(18), f(19), f(20)],
            pad_contact: [a[21] > 0.5, a[22] > 0.5],
            wrist_camera: None,
            fixture: None,
            wrist_force: None,
            wrist_torque: None,
        }
    }

    /// The flat view, in the order of [`OBS_NAMES`].
    pub fn to_array(&self) -> [f32; OBS_DIM] {
        let mut out = [0.0f32; OBS_DIM];
        let values = self
            .joints
            .iter()
            .chain(&self.joint_velocities)
            .chain(&self.object_rel_tcp)
            .copied()
            .chain([self.gripper_opening])
            .chain(self.yaw_features())
            .chain(self.tcp_position)
            .chain(self.pad_contact.map(|c| if c { 1.0 } else { 0.0 }));
        for (slot, v) in out.iter_mut().zip(values) {
            *slot = v as f32;
        }
        out
    }
}
