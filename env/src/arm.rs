//! Driving the arm and the gripper: joint-velocity commands in, joint angles out.
//!
//! Both arm models share one rate limiter: the commanded joint velocity is clamped to the FR3
//! velocity limits and reached with at most `max_acceleration`. The servo arm integrates it and
//! places kinematic links by FK; the multibody arm hands it to the joint velocity motors.

use fairgrasp_kinematics::{ArmModel, Pose};
use nalgebra::Isometry3;
use rapier3d::prelude::*;

use crate::config::ArmModelKind;
use crate::convert::{from_rapier, to_rapier};
use crate::scene::{SceneHandles, finger_anchor};

/// Joint state of the arm, and the velocity the rate limiter has reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmDrive {
    /// Which simulation moves the links.
    pub kind: ArmModelKind,
    /// Joint angles [rad] (servo: the reference itself; multibody: read back each substep).
    pub q: [f64; 6],
    /// Reference joint angles: the integral of the rate-limited command [rad].
    pub q_ref: [f64; 6],
    /// Rate-limited joint velocity command [rad/s].
    pub qd: [f64; 6],
}

/// Multibody joint servo: stiffness [N·m/rad] and damping [N·m·s/rad] of the position motors.
const MOTOR_STIFFNESS: f32 = 2.0e4;
const MOTOR_DAMPING: f32 = 4.0e2;

impl ArmDrive {
    /// A drive at rest at `q`.
    pub fn new(kind: ArmModelKind, q: [f64; 6]) -> Self {
        Self {
            kind,
            q,
            q_ref: q,
            qd: [0.0; 6],
        }
    }

    /// Advances one physics substep of `dt` seconds toward `command` [rad/s]; call before
    /// stepping the world.
    #[allow(clippy::too_many_arguments)]
    pub fn substep(
        &mut self,
        world: &mut PhysicsWorld,
        handles: &SceneHandles,
        model: &ArmModel,
        base: &Pose,
        command: &[f64; 6],
        dt: f64,
        max_acceleration: f64,
    ) {
        for ((qd, spec), &cmd) in self.qd.iter_mut().zip(&model.joints).zip(command) {
            let target = cmd.clamp(-spec.max_velocity, spec.max_velocity);
            *qd += (target - *qd).clamp(-max_acceleration * dt, max_acceleration * dt);
        }
        for i in 0..6 {
            let spec = model.joints[i];
            let next = self.q_ref[i] + self.qd[i] * dt;
            self.q_ref[i] = next.clamp(spec.lower, spec.upper);
            if self.q_ref[i] != next {
                self.qd[i] = 0.0; // stopped at the soft limit
            }
        }
        match self.kind {
            ArmModelKind::Servo => {
                self.q = self.q_ref;
                place_kinematic_arm(world, handles, model, base, &self.q, false);
            }
            ArmModelKind::Multibody => {
                // A position-controlled cobot: PD motors track the reference and its velocity.
                let joints = handles.arm_joints.expect("multibody arm has joint handles");
                for (i, handle) in joints.iter().enumerate() {
                    if let Some((mb, link)) = world.multibody_joints.get_mut(*handle)
                        && let Some(link) = mb.link_mut(link)
                    {
                        let (q, v) = (self.q_ref[i] as f32, self.qd[i] as f32);
                        link.joint.data.set_motor(
                            JointAxis::AngX,
                            q,
                            v,
                            MOTOR_STIFFNESS,
                            MOTOR_DAMPING,
                        );
                    }
                }
            }
        }
    }

    /// Reads the joint angles back from the world (multibody) after a step.
    pub fn sync(&mut self, world: &PhysicsWorld, handles: &SceneHandles) {
        if self.kind == ArmModelKind::Multibody {
            self.q = multibody_joints(world, handles);
        }
    }

    /// Teleports the arm to `q` at rest.
    pub fn teleport(
        &mut self,
        world: &mut PhysicsWorld,
        handles: &SceneHandles,
        model: &ArmModel,
        base: &Pose,
        q: &[f64; 6],
    ) {
        self.q = *q;
        self.q_ref = *q;
        self.qd = [0.0; 6];
        match self.kind {
            ArmModelKind::Servo => place_kinematic_arm(world, handles, model, base, q, true),
            ArmModelKind::Multibody => {
                let joints = handles.arm_joints.expect("multibody arm has joint handles");
                let current = multibody_joints(world, handles);
                let Some((mb, _)) = world.multibody_joints.get_mut(joints[0]) else {
                    return;
                };
                for (i, handle_link) in (1..=6).enumerate() {
                    if let Some(link) = mb.link_mut(handle_link) {
                        link.joint.apply_displacement(&[(q[i] - current[i]) as f32]);
                    }
                }
                mb.generalized_velocity_mut().fill(0.0);
                mb.forward_kinematics(&world.bodies, true);
                mb.update_rigid_bodies(&mut world.bodies, false);
            }
        }
    }
}

/// Joint angles of the multibody arm [rad].
fn multibody_joints(world: &PhysicsWorld, handles: &SceneHandles) -> [f64; 6] {
    let joints = handles.arm_joints.expect("multibody arm has joint handles");
    let mut q = [0.0; 6];
    for (i, handle) in joints.iter().enumerate() {
        if let Some((mb, link)) = world.multibody_joints.get(*handle)
            && let Some(link) = mb.link(link)
        {
            q[i] = link.joint().coords()[3] as f64;
        }
    }
    q
}

/// Places the kinematic links and palm at FK(q); `teleport` also sets the current pose.
fn place_kinematic_arm(
    world: &mut PhysicsWorld,
    handles: &SceneHandles,
    model: &ArmModel,
    base: &Pose,
    q: &[f64; 6],
    teleport: bool,
) {
    let poses = model.link_poses(q);
    let tool0 = base.iso * model.fk_flange(q).iso;
    let targets = handles
        .links
        .iter()
        .zip(poses.iter().map(|p| base.iso * p))
        .chain([(&handles.palm, tool0)]);
    for (handle, pose) in targets {
        if let Some(body) = world.bodies.get_mut(*handle) {
            let pose = to_rapier(&pose);
            if teleport {
                body.set_position(pose, true);
            }
            body.set_next_kinematic_position(pose);
        }
    }
}

/// Closing travel of each finger [m] (0 = open, `finger_travel` = closed), measured from bodies.
pub fn finger_travel(world: &PhysicsWorld, handles: &SceneHandles, model: &ArmModel) -> [f64; 2] {
    let palm = from_rapier(world.bodies[handles.palm].position());
    std::array::from_fn(|f| {
        let (anchor, axis) = finger_anchor(model, f);
        let finger = from_rapier(world.bodies[handles.fingers[f]].position());
        let local = palm.inverse_transform_point(&finger.translation.vector.into());
        (0..3).map(|k| (local[k] - anchor[k]) * axis[k]).sum()
    })
}

/// Closing speed of each finger relative to the palm [m/s].
pub fn finger_travel_rate(
    world: &PhysicsWorld,
    handles: &SceneHandles,
    model: &ArmModel,
) -> [f64; 2] {
    let palm = &world.bodies[handles.palm];
    std::array::from_fn(|f| {
        let (_, axis) = finger_anchor(model, f);
        let finger = &world.bodies[handles.fingers[f]];
        let relative = finger.linvel() - palm.velocity_at_point(finger.translation());
        let axis_world =
            palm.rotation() * Vector::new(axis[0] as f32, axis[1] as f32, axis[2] as f32);
        relative.dot(axis_world) as f64
    })
}

/// Centring stiffness: how much the two squeeze forces differ per metre of asymmetry [N/m].
const CENTRING_GAIN: f64 = 2000.0;
/// Centring damping, per m/s of asymmetry rate [N·s/m] (about critical for fingers + cube).
const CENTRING_DAMPING: f64 = 20.0;

/// Sets the finger motors for a gripper command in [-1, 1] (-1 open, +1 closed).
///
/// Both fingers are force-limited position motors toward the commanded travel. Independent
/// force-limited fingers drift sideways together (CRATES.md pitfall 5), so the two force limits
/// are split around `force` by the asymmetry: a finger that has travelled less pushes harder,
/// which re-centres the pair; the mean squeeze stays `force` [N].
pub fn drive_fingers(
    world: &mut PhysicsWorld,
    handles: &SceneHandles,
    model: &ArmModel,
    command: f64,
    force: f64,
) {
    let travel_max = model.gripper.finger_travel;
    let target = (command.clamp(-1.0, 1.0) + 1.0) / 2.0 * travel_max;
    let [left, right] = finger_travel(world, handles, model);
    let [left_rate, right_rate] = finger_travel_rate(world, handles, model);
    let asymmetry = CENTRING_GAIN * (right - left) + CENTRING_DAMPING * (right_rate - left_rate);
    let correction = asymmetry.clamp(-0.9 * force, 0.9 * force);
    for (f, max_force) in [force + correction, force - correction]
        .into_iter()
        .enumerate()
    {
        if let Some(joint) = world.impulse_joints.get_mut(handles.finger_joints[f], true) {
            joint
                .data
                .set_motor_position(JointAxis::LinX, target as f32, 1.0e4, 1.0e2);
            joint
                .data
                .set_motor_max_force(JointAxis::LinX, max_force as f32);
        }
    }
}

/// The TCP pose in the world.
pub fn tcp_in_world(model: &ArmModel, base: &Pose, q: &[f64; 6]) -> Isometry3<f64> {
    base.iso * model.fk_tcp(q).iso
}
