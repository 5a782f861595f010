//! The simulator facade: everything the env does to rapier, behind named operations.
//!
//! The robot, the task and the scenario code never touch rapier's sets; they ask this facade to
//! place the arm, drive the fingers, place the object, step, and report contacts. Poses cross
//! this boundary as f64 nalgebra isometries in `world` \[m\]; rapier's f32 types stay inside.

use fairgrasp_kinematics::{ArmModel, Pose};
use nalgebra::Isometry3;
use rapier3d::prelude::*;

use crate::config::EnvConfig;
use crate::sim::contacts::{
    CollisionFilter, ContactReport, TouchingPair, Wrench, WrenchStep, analyze, touching_pairs,
};
use crate::sim::convert::{from_rapier, to_rapier};
use crate::sim::finger_drive::{FINGER_DAMPING, FINGER_STIFFNESS, FingerState};
use crate::sim::scene::{SceneHandles, build, finger_anchor};
use crate::sim::snapshot::Snapshot;

/// Multibody joint servo: stiffness \[N·m/rad\] and damping \[N·m·s/rad\] of the position motors.
const MOTOR_STIFFNESS: f32 = 2.0e4;
const MOTOR_DAMPING: f32 = 4.0e2;

/// The farthest a solver contact of the palm or a finger strut may be \[m\]: rapier 0.36 makes
/// speculative contacts out to its prediction distance, 2 cm here (`normalized_prediction_distance`
/// 0.02 × a 1 m length unit), and the palm and struts, a few millimetres to 2 cm above and beside
/// a cube between the pads, gave the solver three such manifolds on every simulated substep. One
/// farther than this acts only if the gap closes by more within the physics step (> 1.2 m/s at
/// 1/240 s). The pads keep rapier's full margin: they close on the cube fast.
pub const FAR_CONTACT: f32 = 0.005;

/// The physics hook that drops the palm's and the finger struts' solver contacts farther than
/// [`FAR_CONTACT`] (the colliders that ask for it are marked in `sim::scene`, where the robot's
/// colliders are inserted).
struct FarContacts;

impl PhysicsHooks for FarContacts {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        if let Some(rigid) = context.rigid_mut() {
            rigid.solver_contacts.retain(|c| c.dist < FAR_CONTACT);
        }
    }
}

/// The rapier world of one env, its named bodies, and the state it resets to.
pub struct Sim {
    world: PhysicsWorld,
    handles: SceneHandles,
    snapshot: Snapshot,
    filter: CollisionFilter,
}

impl Sim {
    /// Builds the world: the arm at `q` \[rad\] on `base` (`T_world_base`), the fingers open, the
    /// cube at `cube_in_world`.
    pub fn build(
        config: &EnvConfig,
        model: &ArmModel,
        base: &Pose,
        q: &[f64; 6],
        cube_in_world: &Isometry3<f64>,
    ) -> Sim {
        let (world, handles) = build(config, model, base, q, cube_in_world);
        Sim {
            snapshot: Snapshot::take(&world),
            filter: CollisionFilter::new(model),
            world,
            handles,
        }
    }

    /// Restores the world as built (bodies, contacts, solver state).
    pub fn restore(&mut self) {
        self.snapshot.restore(&mut self.world);
    }

    /// Advances the physics by one time step.
    pub fn step(&mut self) {
        self.world.step_with_events(&FarContacts, &());
    }

    /// The object's pose in `world`.
    pub fn object_pose(&self) -> Isometry3<f64> {
        from_rapier(self.world.bodies[self.handles.cube].position())
    }

    /// Places the object at rest at `pose` (`world`), with friction coefficient and mass \[kg\].
    pub fn place_object(&mut self, pose: &Isometry3<f64>, friction: f64, mass: f64) {
        if let Some(body) = self.world.bodies.get_mut(self.handles.cube) {
            body.set_position(to_rapier(pose), true);
            body.set_linvel(Vector::ZERO, true);
            body.set_angvel(Vector::ZERO, true);
        }
        if let Some(c) = self.world.colliders.get_mut(self.handles.cube_collider) {
            c.set_friction(friction as f32);
            c.set_mass(mass as f32);
        }
    }

    /// Moves the place task's fixture to `pose` (`world`: its origin is the pocket's centre on
    /// the table top); does nothing without a fixture.
    pub fn place_fixture(&mut self, pose: &Isometry3<f64>) {
        if let Some(body) = self
            .handles
            .fixture
            .and_then(|h| self.world.bodies.get_mut(h))
        {
            body.set_position(to_rapier(pose), true);
        }
    }

    /// Sets the friction coefficient of the fixture's walls; does nothing without a fixture.
    pub fn set_fixture_friction(&mut self, friction: f64) {
        let Some(body) = self.handles.fixture else {
            return;
        };
        let walls: Vec<ColliderHandle> = self.world.bodies[body].colliders().to_vec();
        for h in walls {
            if let Some(c) = self.world.colliders.get_mut(h) {
                c.set_friction(friction as f32);
            }
        }
    }

    /// Turns the object by `angle` \[rad\] about the line through `pivot` along the unit `axis`
    /// (both `world`), keeping its velocities: a turn in the grip, not a new start.
    pub fn turn_object_about(&mut self, pivot: [f64; 3], axis: [f64; 3], angle: f64) {
        let Some(body) = self.world.bodies.get_mut(self.handles.cube) else {
            return;
        };
        let axis = nalgebra::Unit::new_normalize(nalgebra::Vector3::from(axis));
        let pivot = nalgebra::Translation3::from(nalgebra::Vector3::from(pivot));
        let turn =
            pivot * nalgebra::UnitQuaternion::from_axis_angle(&axis, angle) * pivot.inverse();
        let pose = turn * from_rapier(body.position());
        body.set_position(to_rapier(&pose), true);
    }

    /// The fixture's pose in `world`, if the scene has one.
    pub fn fixture_pose(&self) -> Option<Isometry3<f64>> {
        let body = self.world.bodies.get(self.handles.fixture?)?;
        Some(from_rapier(body.position()))
    }

    /// Places the kinematic links and the palm at FK(q) on `base` for the next step; with
    /// `teleport`, also as the current pose (no motion in between).
    pub fn place_kinematic_arm(
        &mut self,
        model: &ArmModel,
        base: &Pose,
        q: &[f64; 6],
        teleport: bool,
    ) {
        let (poses, flange) = model.link_poses_and_flange(q);
        let tool0 = base.iso * flange.iso;
        let targets = self
            .handles
            .links
            .iter()
            .zip(poses.iter().map(|p| base.iso * p))
            .chain([(&self.handles.palm, tool0)]);
        for (handle, pose) in targets {
            if let Some(body) = self.world.bodies.get_mut(*handle) {
                let pose = to_rapier(&pose);
                if teleport {
                    body.set_position(pose, true);
                }
                body.set_next_kinematic_position(pose);
            }
        }
    }

    /// Sets the multibody arm's position motors toward `q_ref` \[rad\] at velocity `qd` \[rad/s\].
    /// Does nothing for a kinematic arm.
    pub fn set_arm_motors(&mut self, q_ref: &[f64; 6], qd: &[f64; 6]) {
        let Some(joints) = self.handles.arm_joints else {
            return;
        };
        for (i, handle) in joints.iter().enumerate() {
            if let Some((mb, link)) = self.world.multibody_joints.get_mut(*handle)
                && let Some(link) = mb.link_mut(link)
            {
                let (q, v) = (q_ref[i] as f32, qd[i] as f32);
                link.joint
                    .data
                    .set_motor(JointAxis::AngX, q, v, MOTOR_STIFFNESS, MOTOR_DAMPING);
            }
        }
    }

    /// Joint angles of the multibody arm \[rad\]; `None` for a kinematic arm.
    pub fn multibody_joints(&self) -> Option<[f64; 6]> {
        let joints = self.handles.arm_joints?;
        let mut q = [0.0; 6];
        for (i, handle) in joints.iter().enumerate() {
            if let Some((mb, link)) = self.world.multibody_joints.get(*handle)
                && let Some(link) = mb.link(link)
            {
                q[i] = link.joint().coords()[3] as f64;
            }
        }
        Some(q)
    }

    /// Moves the multibody arm to `q` \[rad\] at rest. Does nothing for a kinematic arm.
    pub fn teleport_multibody_arm(&mut self, q: &[f64; 6]) {
        let (Some(joints), Some(current)) = (self.handles.arm_joints, self.multibody_joints())
        else {
            return;
        };
        let Some((mb, _)) = self.world.multibody_joints.get_mut(joints[0]) else {
            return;
        };
        for (i, handle_link) in (1..=6).enumerate() {
            if let Some(link) = mb.link_mut(handle_link) {
                link.joint.apply_displacement(&[(q[i] - current[i]) as f32]);
            }
        }
        mb.generalized_velocity_mut().fill(0.0);
        mb.forward_kinematics(&self.world.bodies, true);
        mb.update_rigid_bodies(&mut self.world.bodies, false);
    }

    /// Places both fingers fully open on the flange at FK(q) on `base`, at rest.
    pub fn place_fingers_open(&mut self, model: &ArmModel, base: &Pose, q: &[f64; 6]) {
        let tool0 = base.iso * model.fk_flange(q).iso;
        for f in 0..2 {
            let (anchor, _) = finger_anchor(model, f);
            let pose = tool0 * Isometry3::translation(anchor[0], anchor[1], anchor[2]);
            if let Some(body) = self.world.bodies.get_mut(self.handles.fingers[f]) {
                body.set_position(to_rapier(&pose), true);
                body.set_linvel(Vector::ZERO, true);
                body.set_angvel(Vector::ZERO, true);
            }
        }
    }

    /// Closing travel of each finger \[m\] (0 = open, `finger_travel` = closed), from the bodies.
    pub fn finger_travel(&self, model: &ArmModel) -> [f64; 2] {
        let palm = from_rapier(self.world.bodies[self.handles.palm].position());
        std::array::from_fn(|f| {
            let (anchor, axis) = finger_anchor(model, f);
            let finger = from_rapier(self.world.bodies[self.handles.fingers[f]].position());
            let local = palm.inverse_transform_point(&finger.translation.vector.into());
            (0..3).map(|k| (local[k] - anchor[k]) * axis[k]).sum()
        })
    }

    /// Closing speed of each finger relative to the palm \[m/s\].
    pub fn finger_travel_rate(&self, model: &ArmModel) -> [f64; 2] {
        let palm = &self.world.bodies[self.handles.palm];
        std::array::from_fn(|f| {
            let (_, axis) = finger_anchor(model, f);
            let finger = &self.world.bodies[self.handles.fingers[f]];
            let relative = finger.linvel() - palm.velocity_at_point(finger.translation());
            let axis_world =
                palm.rotation() * Vector::new(axis[0] as f32, axis[1] as f32, axis[2] as f32);
            relative.dot(axis_world) as f64
        })
    }

    /// Drives both fingers toward travel `target` \[m\], each with its own force limit \[N\].
    pub fn set_finger_motors(&mut self, target: f64, max_forces: [f64; 2]) {
        for (f, max_force) in max_forces.into_iter().enumerate() {
            if let Some(joint) = self
                .world
                .impulse_joints
                .get_mut(self.handles.finger_joints[f], true)
            {
                joint.data.set_motor_position(
                    JointAxis::LinX,
                    target as f32,
                    FINGER_STIFFNESS as f32,
                    FINGER_DAMPING as f32,
                );
                joint
                    .data
                    .set_motor_max_force(JointAxis::LinX, max_force as f32);
            }
        }
    }

    /// Places each finger at its closing travel \[m\] on the flange at FK(`q`) on `base`, moving
    /// with the palm (its velocity from the flange's motion `previous → q` over `dt` \[s\]) plus
    /// its travel rate \[m/s\]; the finger joints' solver impulses restart from zero.
    pub fn place_fingers(
        &mut self,
        model: &ArmModel,
        base: &Pose,
        (previous, q): (&[f64; 6], &[f64; 6]),
        dt: f64,
        fingers: [FingerState; 2],
    ) {
        let tool0 = base.iso * model.fk_flange(q).iso;
        let before = base.iso * model.fk_flange(previous).iso;
        let angvel = (tool0.rotation * before.rotation.inverse()).scaled_axis() / dt;
        let origin_velocity = (tool0.translation.vector - before.translation.vector) / dt;
        for (f, state) in fingers.iter().enumerate() {
            let (anchor, axis) = finger_anchor(model, f);
            let local =
                nalgebra::Vector3::from(anchor) + nalgebra::Vector3::from(axis) * state.travel;
            let pose = tool0 * Isometry3::translation(local.x, local.y, local.z);
            let arm = pose.translation.vector - tool0.translation.vector;
            let axis_world = tool0.rotation * nalgebra::Vector3::from(axis);
            let linvel = origin_velocity + angvel.cross(&arm) + axis_world * state.rate;
            if let Some(body) = self.world.bodies.get_mut(self.handles.fingers[f]) {
                body.set_position(to_rapier(&pose), true);
                body.set_linvel(crate::sim::convert::vec3(linvel.into()), true);
                body.set_angvel(crate::sim::convert::vec3(angvel.into()), true);
            }
            if let Some(joint) = self
                .world
                .impulse_joints
                .get_mut(self.handles.finger_joints[f], true)
            {
                joint.impulses = Default::default();
            }
        }
    }

    /// Is the object at rest: moving slower than `max_speed` \[m/s\] and turning slower than
    /// `max_turn_rate` \[rad/s\] (a sleeping object is)?
    pub fn object_at_rest(&self, max_speed: f64, max_turn_rate: f64) -> bool {
        let body = &self.world.bodies[self.handles.cube];
        body.is_sleeping()
            || (f64::from(body.linvel().length()) < max_speed
                && f64::from(body.angvel().length()) < max_turn_rate)
    }

    /// The first non-finite body state, if any.
    pub fn fault(&self) -> Option<String> {
        self.world.bodies.iter().find_map(|(handle, body)| {
            let p = body.position();
            let finite = p.translation.is_finite()
                && p.rotation.is_finite()
                && body.linvel().is_finite()
                && body.angvel().is_finite();
            (!finite)
                .then(|| format!("rigid body {handle:?} has a non-finite position or velocity"))
        })
    }

    /// What the narrow phase says now: collisions, pad contacts, pad penetration. The servo
    /// arm's link, palm and table pairs are not in it ([`crate::sim::scene::build`]).
    pub fn contacts(&self) -> ContactReport {
        analyze(&self.world, &self.handles, &self.filter)
    }

    /// Every touching pair of the narrow phase now, deepest first, with how it is judged.
    pub fn touching_pairs(&self) -> Vec<TouchingPair> {
        touching_pairs(&self.world, &self.handles, &self.filter)
    }

    /// Test and debugging access to the physics world.
    pub fn world_mut(&mut self) -> (&mut PhysicsWorld, &SceneHandles) {
        (&mut self.world, &self.handles)
    }

    /// What a six-axis wrist sensor reads after the last physics step, tared: force \[N\] and
    /// torque \[N·m\] about `sensor_origin`, all in `world`
    /// ([`crate::sim::contacts::wrist_wrench`]).
    /// With `friction`, the contacts' friction is read too.
    pub fn wrist_wrench(&self, holding: bool, sensor_origin: [f64; 3], friction: bool) -> Wrench {
        let step = WrenchStep {
            dt: f64::from(self.world.integration_parameters.dt),
            solver_iterations: self.world.integration_parameters.num_solver_iterations,
            friction,
        };
        let about = Vec3::new(
            sensor_origin[0] as f32,
            sensor_origin[1] as f32,
            sensor_origin[2] as f32,
        );
        crate::sim::contacts::wrist_wrench(&self.world, &self.handles.parts, step, holding, about)
    }

    /// The strongest robot–cube or robot–table contact force of the last physics step
    /// ([`crate::sim::contacts::strongest_robot_contact`]): what a cobot's collision detection watches.
    pub fn strongest_robot_contact(&self) -> Option<crate::sim::contacts::RobotContactForce> {
        let dt = f64::from(self.world.integration_parameters.dt);
        crate::sim::contacts::strongest_robot_contact(
            &self.world,
            &self.handles.parts,
            self.handles.cube_collider,
            self.handles.table_collider,
            dt,
        )
    }
}
