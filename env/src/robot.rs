//! The robot: the FR3 arm (servo or multibody) and its force-limited parallel gripper. It applies
//! an action and reports joint and gripper state; the simulator is reached only through [`Sim`].
//!
//! Both arm models share one rate limiter: the commanded joint velocity is clamped to the FR3
//! velocity limits and reached with at most `max_acceleration`. The servo arm integrates it and
//! places kinematic links by FK; the multibody arm hands it to the joint position motors.

use fairgrasp_kinematics::{ArmModel, Pose};

use crate::config::{ArmModelKind, EnvConfig};
use crate::sim::Sim;

/// Centring stiffness: how much the two squeeze forces differ per metre of asymmetry [N/m].
const CENTRING_GAIN: f64 = 2000.0;
/// Centring damping, per m/s of asymmetry rate [N·s/m] (about critical for fingers + cube).
const CENTRING_DAMPING: f64 = 20.0;

/// The arm and gripper state the env integrates.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// Which simulation moves the links.
    pub kind: ArmModelKind,
    /// The arm's kinematic model.
    pub model: ArmModel,
    /// `base_link` in `world`.
    pub base: Pose,
    /// Joint angles [rad] (servo: the reference itself; multibody: read back each substep).
    pub q: [f64; 6],
    /// Reference joint angles: the integral of the rate-limited command [rad].
    pub q_ref: [f64; 6],
    /// Rate-limited joint velocity command [rad/s].
    pub qd: [f64; 6],
    /// Gripper command in [-1, 1] (-1 open, +1 closed).
    pub gripper_command: f64,
    /// Joint acceleration limit [rad/s²].
    max_acceleration: f64,
    /// Squeeze force of each finger [N].
    grip_force: f64,
}

impl Robot {
    /// The robot a config describes, at rest at its home joints, gripper open.
    pub fn new(config: &EnvConfig, model: ArmModel, base: Pose) -> Robot {
        let q = config.arm.home_joints;
        Robot {
            kind: config.arm.model,
            model,
            base,
            q,
            q_ref: q,
            qd: [0.0; 6],
            gripper_command: -1.0,
            max_acceleration: config.arm.max_acceleration,
            grip_force: config.gripper.force,
        }
    }

    /// Moves arm and fingers to `q` [rad] at rest, gripper open.
    pub fn teleport(&mut self, sim: &mut Sim, q: &[f64; 6]) {
        self.q = *q;
        self.q_ref = *q;
        self.qd = [0.0; 6];
        self.gripper_command = -1.0;
        match self.kind {
            ArmModelKind::Servo => sim.place_kinematic_arm(&self.model, &self.base, q, true),
            ArmModelKind::Multibody => sim.teleport_multibody_arm(q),
        }
        sim.place_fingers_open(&self.model, &self.base, q);
    }

    /// Sets up one physics substep of `dt` [s] toward joint velocities `command` [rad/s]:
    /// rate-limits, integrates, places or drives the arm, drives the fingers. Call before
    /// stepping the simulator, and [`Robot::sync`] after.
    pub fn substep(&mut self, sim: &mut Sim, command: &[f64; 6], dt: f64) {
        let a = self.max_acceleration * dt;
        for ((qd, spec), &cmd) in self.qd.iter_mut().zip(&self.model.joints).zip(command) {
            let target = cmd.clamp(-spec.max_velocity, spec.max_velocity);
            *qd += (target - *qd).clamp(-a, a);
        }
        for i in 0..6 {
            let spec = self.model.joints[i];
            let next = self.q_ref[i] + self.qd[i] * dt;
            self.q_ref[i] = next.clamp(spec.lower, spec.upper);
            if self.q_ref[i] != next {
                self.qd[i] = 0.0; // stopped at the soft limit
            }
        }
        match self.kind {
            ArmModelKind::Servo => {
                self.q = self.q_ref;
                sim.place_kinematic_arm(&self.model, &self.base, &self.q, false);
            }
            // A position-controlled cobot: PD motors track the reference and its velocity.
            ArmModelKind::Multibody => sim.set_arm_motors(&self.q_ref, &self.qd),
        }
        self.drive_fingers(sim);
    }

    /// Reads the joint angles back after a simulator step (multibody).
    pub fn sync(&mut self, sim: &Sim) {
        if let Some(q) = sim.multibody_joints() {
            self.q = q;
        }
    }

    /// Sets the finger motors for the gripper command.
    ///
    /// Both fingers are force-limited position motors toward the commanded travel. Independent
    /// force-limited fingers drift sideways together, so the two force limits are split around
    /// the grip force by the asymmetry: a finger that has travelled less pushes harder, which
    /// re-centres the pair; the mean squeeze stays the grip force [N].
    fn drive_fingers(&self, sim: &mut Sim) {
        let force = self.grip_force;
        let target =
            (self.gripper_command.clamp(-1.0, 1.0) + 1.0) / 2.0 * self.model.gripper.finger_travel;
        let [left, right] = sim.finger_travel(&self.model);
        let [left_rate, right_rate] = sim.finger_travel_rate(&self.model);
        let asymmetry =
            CENTRING_GAIN * (right - left) + CENTRING_DAMPING * (right_rate - left_rate);
        let correction = asymmetry.clamp(-0.9 * force, 0.9 * force);
        sim.set_finger_motors(target, [force + correction, force - correction]);
    }

    /// Distance between the pads' inner faces [m] (0.085 fully open).
    pub fn gripper_opening(&self, sim: &Sim) -> f64 {
        let travel = sim.finger_travel(&self.model);
        self.model.gripper.opening(0.5 * (travel[0] + travel[1]))
    }

    /// The TCP pose in `base_link` at the current joints.
    pub fn tcp_in_base(&self) -> Pose {
        self.model.fk_tcp(&self.q)
    }

    /// The TCP pose in `world` at the current joints.
    pub fn tcp_in_world(&self) -> Pose {
        self.base.compose(&self.tcp_in_base())
    }

    /// A non-finite joint angle, if any.
    pub fn fault(&self) -> Option<String> {
        (!self.q.iter().all(|v| v.is_finite()))
            .then(|| format!("joint angles are not finite: {:?}", self.q))
    }
}
