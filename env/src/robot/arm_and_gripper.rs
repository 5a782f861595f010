//! The robot: the FR3 arm (servo or multibody) and its force-limited parallel gripper. It applies
//! an action and reports joint and gripper state; the simulator is reached only through [`Sim`].
//!
//! Both arm models share one rate limiter: the commanded joint velocity is clamped to the FR3
//! velocity limits and reached with at most `max_acceleration`. The servo arm integrates it and
//! places kinematic links by FK; the multibody arm hands it to the joint position motors.

use fairgrasp_kinematics::{ArmModel, Pose};

use crate::config::{ArmSimulation, EnvConfig};
use crate::sim::Sim;
use crate::sim::finger_drive::{FingerDrive, FingerState};
use crate::sim::scene::finger_anchor;

/// Centring stiffness: how much the two squeeze forces differ per metre of asymmetry \[N/m\].
const CENTRING_GAIN: f64 = 2000.0;
/// Centring damping, per m/s of asymmetry rate \[N·s/m\] (about critical for fingers + cube).
const CENTRING_DAMPING: f64 = 20.0;

/// What a substep changes: joints, reference, joint velocity command, fingers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionState {
    /// Joint angles \[rad\].
    pub q: [f64; 6],
    /// Reference joint angles \[rad\].
    pub q_ref: [f64; 6],
    /// Rate-limited joint velocity command \[rad/s\].
    pub qd: [f64; 6],
    /// Finger travel \[m\] and rate \[m/s\].
    pub fingers: [FingerState; 2],
}

/// The arm and gripper state the env integrates.
#[derive(Clone, Debug, PartialEq)]
pub struct Robot {
    /// Which simulation moves the links.
    pub kind: ArmSimulation,
    /// The arm's kinematic model.
    pub model: ArmModel,
    /// `base_link` in `world`.
    pub base: Pose,
    /// Joint angles \[rad\] (servo: the reference itself; multibody: read back each substep).
    pub q: [f64; 6],
    /// Reference joint angles: the integral of the rate-limited command \[rad\].
    pub q_ref: [f64; 6],
    /// Rate-limited joint velocity command \[rad/s\].
    pub qd: [f64; 6],
    /// Gripper command in [-1, 1] (-1 open, +1 closed).
    pub gripper_command: f64,
    /// Left and right finger: closing travel \[m\] and rate \[m/s\] relative to the palm (read back
    /// from the simulator after a physics substep, integrated by the drive in free space).
    pub fingers: [FingerState; 2],
    /// Joint acceleration limit \[rad/s²\].
    max_acceleration: f64,
    /// Squeeze force of each finger \[N\] (the config's `gripper.force` unless a policy asks for
    /// another: [`Robot::set_grip_force`]).
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
            fingers: [FingerState::default(); 2],
            max_acceleration: config.arm.max_acceleration,
            grip_force: config.gripper.force,
        }
    }

    /// The state a substep changes (to undo a tentative free-space step).
    pub fn motion(&self) -> MotionState {
        MotionState {
            q: self.q,
            q_ref: self.q_ref,
            qd: self.qd,
            fingers: self.fingers,
        }
    }

    /// Restores a state taken with [`Robot::motion`].
    pub fn set_motion(&mut self, state: &MotionState) {
        self.q = state.q;
        self.q_ref = state.q_ref;
        self.qd = state.qd;
        self.fingers = state.fingers;
    }

    /// Moves arm and fingers to `q` \[rad\] at rest, gripper open.
    pub fn teleport(&mut self, sim: &mut Sim, q: &[f64; 6]) {
        self.q = *q;
        self.q_ref = *q;
        self.qd = [0.0; 6];
        self.gripper_command = -1.0;
        self.fingers = [FingerState::default(); 2];
        match self.kind {
            ArmSimulation::Servo => sim.place_kinematic_arm(&self.model, &self.base, q, true),
            ArmSimulation::Multibody => sim.teleport_multibody_arm(q),
        }
        sim.place_fingers_open(&self.model, &self.base, q);
    }

    /// Advances the reference by one substep of `dt` \[s\] toward joint velocities `command`
    /// \[rad/s\]: clamps to the velocity limits, reaches them at most at the acceleration limit,
    /// and stops at the soft joint limits.
    fn advance_reference(&mut self, command: &[f64; 6], dt: f64) {
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
    }

    /// Sets up one physics substep of `dt` \[s\] toward joint velocities `command` \[rad/s\]:
    /// rate-limits, integrates, places or drives the arm, drives the fingers. Call before
    /// stepping the simulator, and [`Robot::sync`] after.
    pub fn substep(&mut self, sim: &mut Sim, command: &[f64; 6], dt: f64) {
        self.advance_reference(command, dt);
        match self.kind {
            ArmSimulation::Servo => {
                self.q = self.q_ref;
                sim.place_kinematic_arm(&self.model, &self.base, &self.q, false);
            }
            // A position-controlled cobot: PD motors track the reference and its velocity.
            ArmSimulation::Multibody => sim.set_arm_motors(&self.q_ref, &self.qd),
        }
        let (target, forces) = self.finger_motor_setpoint();
        sim.set_finger_motors(target, forces);
    }

    /// One substep of `dt` \[s\] of the servo arm in free space, without the simulator: the
    /// joints follow the rate-limited reference and each finger follows its motor
    /// ([`FingerState::advance`]) with `gravity_along_axis` \[m/s²\] (see
    /// [`Robot::finger_gravity`]).
    pub fn free_substep(&mut self, command: &[f64; 6], dt: f64, gravity_along_axis: [f64; 2]) {
        self.advance_reference(command, dt);
        self.q = self.q_ref;
        let (target, forces) = self.finger_motor_setpoint();
        for f in 0..2 {
            let drive = FingerDrive {
                target,
                max_force: forces[f],
                mass: self.model.gripper.finger_mass,
                gravity_along_axis: gravity_along_axis[f],
                limit: self.model.gripper.finger_travel,
            };
            self.fingers[f] = self.fingers[f].advance(&drive, dt);
        }
    }

    /// Gravity's component along each finger's closing axis at the current joints \[m/s²\].
    pub fn finger_gravity(&self) -> [f64; 2] {
        let palm = self.base.iso.rotation * self.model.fk_flange(&self.q).iso.rotation;
        std::array::from_fn(|f| {
            let (_, axis) = finger_anchor(&self.model, f);
            -9.81 * (palm * nalgebra::Vector3::from(axis)).z
        })
    }

    /// Reads the joint angles (multibody) and the fingers back after a simulator step.
    pub fn sync(&mut self, sim: &Sim) {
        if let Some(q) = sim.multibody_joints() {
            self.q = q;
        }
        let travel = sim.finger_travel(&self.model);
        let rate = sim.finger_travel_rate(&self.model);
        self.fingers = std::array::from_fn(|f| FingerState {
            travel: travel[f],
            rate: rate[f],
        });
    }

    /// Puts the simulator's servo arm and fingers where this robot is, moving as it moves:
    /// the hand-over from free-space steps back to physics. The links are placed at FK(q); each
    /// finger at its travel, with the palm's velocity (from the joint velocities) plus its
    /// travel rate, so that no velocity is injected.
    pub fn hand_over(&self, sim: &mut Sim, dt: f64) {
        sim.place_kinematic_arm(&self.model, &self.base, &self.q, true);
        let previous: [f64; 6] = std::array::from_fn(|i| self.q[i] - self.qd[i] * dt);
        sim.place_fingers(
            &self.model,
            &self.base,
            (&previous, &self.q),
            dt,
            self.fingers,
        );
    }

    /// The fingers' motor target travel \[m\] and each finger's force limit \[N\].
    ///
    /// Both fingers are force-limited position motors toward the commanded travel. Independent
    /// force-limited fingers drift sideways together, so the two force limits are split around
    /// the grip force by the asymmetry: a finger that has travelled less pushes harder, which
    /// re-centres the pair; the mean squeeze stays the grip force \[N\].
    fn finger_motor_setpoint(&self) -> (f64, [f64; 2]) {
        let force = self.grip_force;
        let target =
            (self.gripper_command.clamp(-1.0, 1.0) + 1.0) / 2.0 * self.model.gripper.finger_travel;
        let [left, right] = self.fingers;
        let asymmetry = CENTRING_GAIN * (right.travel - left.travel)
            + CENTRING_DAMPING * (right.rate - left.rate);
        let correction = asymmetry.clamp(-0.9 * force, 0.9 * force);
        (target, [force + correction, force - correction])
    }

    /// Squeeze force of each finger \[N\].
    pub fn grip_force(&self) -> f64 {
        self.grip_force
    }

    /// Sets the squeeze force of each finger \[N\] (checked by the caller).
    pub fn set_grip_force(&mut self, newtons: f64) {
        self.grip_force = newtons;
    }

    /// Distance between the pads' inner faces \[m\] (0.085 fully open).
    pub fn gripper_opening(&self) -> f64 {
        let [left, right] = self.fingers;
        self.model
            .gripper
            .opening(0.5 * (left.travel + right.travel))
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
        if !self.q.iter().all(|v| v.is_finite()) {
            return Some(format!("joint angles are not finite: {:?}", self.q));
        }
        let finite = |s: &FingerState| s.travel.is_finite() && s.rate.is_finite();
        (!self.fingers.iter().all(finite))
            .then(|| format!("finger states are not finite: {:?}", self.fingers))
    }
}
