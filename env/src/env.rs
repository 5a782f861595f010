//! `GraspEnv`: the gym-style interface. `reset(seed)` and `step(&Action)`.
//!
//! An action is 6 joint-velocity commands and 1 gripper command, each in [-1, 1]: joints move at
//! `action · arm.action_scale` rad/s; the gripper closes toward travel `(g + 1)/2 · 42.5 mm`
//! (−1 open, +1 closed) with a limited force. `terminated` means success or failure, `truncated`
//! the time limit or a physics fault; never both.

use crate::arm::{ArmDrive, drive_fingers, finger_travel, tcp_in_world};
use crate::config::EnvConfig;
use crate::contacts::{CollisionFilter, ContactReport, analyze};
use crate::convert::{from_rapier, to_rapier};
use crate::obs::Observation;
use crate::randomize::{Scenario, object_pose_in_base};
use crate::scene::{SceneHandles, build};
use crate::snapshot::Snapshot;
pub use crate::step::{Action, EnvError, Info, Step};
use crate::task::{Failure, TaskState, is_off_table, is_success, reward};
use fairgrasp_kinematics::{ArmKind, ArmModel, Pose};
use nalgebra::Isometry3;
use rapier3d::prelude::*;

/// Physics substeps run at reset so the object settles on the table.
const SETTLE_SUBSTEPS: usize = 24;

/// The FR3 grasping environment.
pub struct GraspEnv {
    config: EnvConfig,
    model: ArmModel,
    base: Pose,
    world: PhysicsWorld,
    handles: SceneHandles,
    filter: CollisionFilter,
    snapshot: Snapshot,
    drive: ArmDrive,
    gripper_command: f64,
    object_rest_z: f64,
    steps: usize,
    done: bool,
    scenario: Option<Scenario>,
    last_obs_joints: [f64; 6],
}

impl GraspEnv {
    /// Builds the world once (validating the config); call [`GraspEnv::reset`] before stepping.
    pub fn new(config: EnvConfig) -> Result<Self, EnvError> {
        config.validate()?;
        let model = ArmKind::Fr3.model();
        let base = Pose::from_xyz_rpy(config.arm.base_xyz, config.arm.base_rpy);
        let (world, handles, snapshot) = Self::build_world(&config, &model, &base);
        let drive = ArmDrive::new(config.arm.model, config.arm.home_joints);
        Ok(Self {
            filter: CollisionFilter::new(&model),
            last_obs_joints: config.arm.home_joints,
            config,
            model,
            base,
            world,
            handles,
            snapshot,
            drive,
            gripper_command: -1.0,
            object_rest_z: 0.0,
            steps: 0,
            done: true,
            scenario: None,
        })
    }

    fn build_world(
        config: &EnvConfig,
        model: &ArmModel,
        base: &Pose,
    ) -> (PhysicsWorld, SceneHandles, Snapshot) {
        let cube = object_pose_in_base(config, base, config.scene.cube_xy, 0.0);
        let cube_world = base.iso * cube.iso * Isometry3::translation(0.0, 0.0, 0.001);
        let (world, handles) = build(config, model, base, &config.arm.home_joints, &cube_world);
        let snapshot = Snapshot::take(&world);
        (world, handles, snapshot)
    }

    /// Replaces the randomisation (e.g. from a curriculum); takes effect at the next reset.
    pub fn set_randomization(
        &mut self,
        randomization: crate::config::RandomizationConfig,
    ) -> Result<(), EnvError> {
        let mut config = self.config.clone();
        config.randomization = randomization;
        config.validate()?;
        self.config = config;
        Ok(())
    }

    /// The configuration in force.
    pub fn config(&self) -> &EnvConfig {
        &self.config
    }

    /// The arm model.
    pub fn model(&self) -> &ArmModel {
        &self.model
    }

    /// `base_link` in the world.
    pub fn base_in_world(&self) -> &Pose {
        &self.base
    }

    /// Soft reset to the scenario drawn from `seed`.
    pub fn reset(&mut self, seed: u64) -> Result<(Observation, Info), EnvError> {
        let scenario = Scenario::sample(&self.config, &self.model, &self.base, seed)?;
        Ok(self.reset_to(&scenario))
    }

    /// Hard reset: rebuilds the world from nothing, then resets to the scenario of `seed`.
    pub fn hard_reset(&mut self, seed: u64) -> Result<(Observation, Info), EnvError> {
        let (world, handles, snapshot) = Self::build_world(&self.config, &self.model, &self.base);
        (self.world, self.handles, self.snapshot) = (world, handles, snapshot);
        self.reset(seed)
    }

    /// Soft reset to a given scenario: restores the built world, then places the arm, fingers
    /// and object and lets the object settle.
    pub fn reset_to(&mut self, scenario: &Scenario) -> (Observation, Info) {
        self.snapshot.restore(&mut self.world);
        let object = object_pose_in_base(
            &self.config,
            &self.base,
            scenario.object_xy,
            scenario.object_yaw,
        );
        let object_world = self.base.iso * object.iso * Isometry3::translation(0.0, 0.0, 0.001);
        if let Some(body) = self.world.bodies.get_mut(self.handles.cube) {
            body.set_position(to_rapier(&object_world), true);
            body.set_linvel(Vector::ZERO, true);
            body.set_angvel(Vector::ZERO, true);
        }
        if let Some(c) = self.world.colliders.get_mut(self.handles.cube_collider) {
            c.set_friction(scenario.friction as f32);
            c.set_mass(scenario.mass as f32);
        }
        self.drive = ArmDrive::new(self.config.arm.model, scenario.start_joints);
        let q = scenario.start_joints;
        self.drive
            .teleport(&mut self.world, &self.handles, &self.model, &self.base, &q);
        self.place_fingers_open(&q);
        self.gripper_command = -1.0;
        for _ in 0..SETTLE_SUBSTEPS {
            self.physics_substep(&[0.0; 6]);
        }
        self.object_rest_z = self.object_pose().translation.z;
        self.steps = 0;
        self.done = false;
        self.scenario = Some(*scenario);
        self.last_obs_joints = self.drive.q;
        let info = Info {
            scenario: Some(*scenario),
            ..Info::default()
        };
        (self.observe([0.0; 6]), info)
    }

    fn place_fingers_open(&mut self, q: &[f64; 6]) {
        let tool0 = self.base.iso * self.model.fk_flange(q).iso;
        for f in 0..2 {
            let (anchor, _) = crate::scene::finger_anchor(&self.model, f);
            let pose = tool0 * Isometry3::translation(anchor[0], anchor[1], anchor[2]);
            if let Some(body) = self.world.bodies.get_mut(self.handles.fingers[f]) {
                body.set_position(to_rapier(&pose), true);
                body.set_linvel(Vector::ZERO, true);
                body.set_angvel(Vector::ZERO, true);
            }
        }
    }

    fn physics_substep(&mut self, joint_command: &[f64; 6]) {
        let dt = self.config.physics.dt;
        self.drive.substep(
            &mut self.world,
            &self.handles,
            &self.model,
            &self.base,
            joint_command,
            dt,
            self.config.arm.max_acceleration,
        );
        drive_fingers(
            &mut self.world,
            &self.handles,
            &self.model,
            self.gripper_command,
            self.config.gripper.force,
        );
        self.world.step();
        self.drive.sync(&self.world, &self.handles);
    }

    /// Applies one action for `physics.substeps` physics steps.
    pub fn step(&mut self, action: &Action) -> Result<Step, EnvError> {
        if self.done {
            return Err(EnvError::EpisodeOver);
        }
        if let Some((index, &value)) = action.0.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(EnvError::NonFiniteAction { index, value });
        }
        let clipped = action.0.map(|v| v.clamp(-1.0, 1.0));
        let command: [f64; 6] = std::array::from_fn(|i| clipped[i] * self.config.arm.action_scale);
        self.gripper_command = clipped[6];
        let q_before = self.drive.q;
        for _ in 0..self.config.physics.substeps {
            self.physics_substep(&command);
        }
        self.steps += 1;
        let env_dt = self.config.physics.dt * self.config.physics.substeps as f64;
        let velocities = std::array::from_fn(|i| (self.drive.q[i] - q_before[i]) / env_dt);
        let mut info = Info {
            step: self.steps,
            scenario: self.scenario,
            ..Info::default()
        };
        if let Some(fault) = self.physics_fault() {
            self.done = true;
            info.physics_fault = Some(fault);
            let obs = self.observe([0.0; 6]);
            return Ok(Step {
                obs,
                reward: 0.0,
                terminated: false,
                truncated: true,
                info,
            });
        }
        // One contact scan serves the observation and the collision check.
        let contacts = analyze(&self.world, &self.handles, &self.filter);
        let obs = self.observe_with(velocities, &contacts);
        let state = self.task_state(&obs);
        let success = is_success(&state, &self.config.task);
        let collision = contacts.collision.map(|(a, b, depth)| {
            info.collision_depth_m = Some(depth);
            Failure::Collision(
                a.name(&self.model).to_string(),
                b.name(&self.model).to_string(),
            )
        });
        info.success = success;
        info.failure = if success {
            None
        } else {
            collision
                .clone()
                .or_else(|| is_off_table(&state).then_some(Failure::ObjectOffTable))
        };
        let terminated = success
            || (collision.is_some() && self.config.task.terminate_on_collision)
            || info.failure == Some(Failure::ObjectOffTable);
        let truncated = !terminated && self.steps >= self.config.task.max_steps;
        let reward = reward(&state, success, collision.is_some(), &self.config.task);
        self.done = terminated || truncated;
        Ok(Step {
            obs,
            reward,
            terminated,
            truncated,
            info,
        })
    }

    /// The first non-finite body state, if any.
    fn physics_fault(&self) -> Option<String> {
        for (handle, body) in self.world.bodies.iter() {
            let p = body.position();
            let finite = p.translation.is_finite()
                && p.rotation.is_finite()
                && body.linvel().is_finite()
                && body.angvel().is_finite();
            if !finite {
                return Some(format!(
                    "rigid body {handle:?} has a non-finite position or velocity"
                ));
            }
        }
        (!self.drive.q.iter().all(|v| v.is_finite()))
            .then(|| format!("joint angles are not finite: {:?}", self.drive.q))
    }

    fn object_pose(&self) -> Isometry3<f64> {
        from_rapier(self.world.bodies[self.handles.cube].position())
    }

    fn task_state(&self, obs: &Observation) -> TaskState {
        let object = self.object_pose().translation.vector;
        let tcp = tcp_in_world(&self.model, &self.base, &obs.joints)
            .translation
            .vector;
        let base_xy = self.base.xyz();
        TaskState {
            object: [object.x, object.y, object.z],
            object_rest_z: self.object_rest_z,
            tcp: [tcp.x, tcp.y, tcp.z],
            pad_contact: obs.pad_contact,
            table_height: self.config.scene.table_height,
            object_xy_from_table_centre: [object.x - base_xy[0], object.y - base_xy[1]],
            table_half_size: self.config.scene.table_size.map(|s| s / 2.0),
        }
    }

    fn observe(&self, joint_velocities: [f64; 6]) -> Observation {
        let contacts = analyze(&self.world, &self.handles, &self.filter);
        self.observe_with(joint_velocities, &contacts)
    }

    fn observe_with(&self, joint_velocities: [f64; 6], contacts: &ContactReport) -> Observation {
        let q = self.drive.q;
        let tcp = self.model.fk_tcp(&q);
        let object_base = self.base.iso.inverse() * self.object_pose();
        let (position_error, yaw_error) = self.scenario.map_or(([0.0; 3], 0.0), |s| {
            (s.observed_position_error, s.observed_yaw_error)
        });
        let observed = object_base.translation.vector + nalgebra::Vector3::from(position_error);
        let rel = observed - tcp.iso.translation.vector;
        let travel = finger_travel(&self.world, &self.handles, &self.model);
        let opening = self.model.gripper.opening(0.5 * (travel[0] + travel[1]));
        Observation {
            joints: q,
            joint_velocities,
            object_rel_tcp: [rel.x, rel.y, rel.z],
            gripper_opening: opening,
            object_yaw: yaw_about_z(&object_base) + yaw_error,
            tcp_position: tcp.xyz(),
            pad_contact: contacts.pad_contact,
        }
    }

    /// The object pose in `base_link`.
    pub fn object_in_base(&self) -> Pose {
        Pose {
            iso: self.base.iso.inverse() * self.object_pose(),
        }
    }

    /// The TCP pose in `base_link` at the current joints.
    pub fn tcp_in_base(&self) -> Pose {
        self.model.fk_tcp(&self.drive.q)
    }

    /// Current finger travels [m] (0 open … 0.0425 closed).
    pub fn finger_travel(&self) -> [f64; 2] {
        finger_travel(&self.world, &self.handles, &self.model)
    }

    /// What the narrow phase says now: collisions, pad contacts, pad penetration.
    pub fn contacts(&self) -> crate::contacts::ContactReport {
        analyze(&self.world, &self.handles, &self.filter)
    }

    /// Every touching pair of the narrow phase now, deepest first, with how it is judged.
    pub fn touching_pairs(&self) -> Vec<crate::contacts::TouchingPair> {
        crate::contacts::touching_pairs(&self.world, &self.handles, &self.filter)
    }

    /// Current joint angles [rad].
    pub fn joints(&self) -> [f64; 6] {
        self.drive.q
    }

    /// Test and debugging access to the physics world.
    pub fn world_mut(&mut self) -> (&mut PhysicsWorld, &SceneHandles) {
        (&mut self.world, &self.handles)
    }
}

/// Yaw of a pose about z, taken from where its x axis points in the xy plane [rad].
fn yaw_about_z(iso: &Isometry3<f64>) -> f64 {
    let x = iso.rotation * nalgebra::Vector3::x();
    x.y.atan2(x.x)
}
