//! The parts a [`GraspEnv::step`] is made of: applying the action, the free-space shortcut, the
//! task's view of the state, the observation, and the episode's record.

use crate::config::ArmSimulation;
use crate::env::free_space::{REST_SPEED, REST_TURN_RATE};
use crate::env::grasp_env::GraspEnv;
use crate::env::obs::Observation;
use crate::env::step::{Action, EnvError, Info, ServoSetpoint, Step};
use crate::scenario::perception::{observe_object, wrist_view};
use crate::sim::contacts::ContactReport;
use crate::sim::part::Part;
use crate::task::episode::{Ending, StepFacts};
use crate::task::state::TaskState;
use crate::task::{Failure, Judgement, judge, judge_protective_stop, void_success_after_collision};
use fairgrasp_kinematics::ArmModel;

/// Gain of a servo step's feedback on the joints' distance from the setpoint \[1/s\]: a tenth of
/// the error corrected per 1/240 s substep, the feedforward velocity doing the rest.
const SERVO_GAIN: f64 = 24.0;

/// How the arm moves during one env step.
#[derive(Clone, Copy)]
pub(super) enum Drive<'a> {
    /// One joint-velocity command \[rad/s\] for every substep (an [`Action`]).
    Velocity([f64; 6]),
    /// A setpoint per substep (a servo stream).
    Servo(&'a [ServoSetpoint]),
}

impl Drive<'_> {
    /// The joint-velocity command \[rad/s\] of substep `j`, from the reference `q_ref` \[rad\]:
    /// the action's, or the setpoint's velocity plus [`SERVO_GAIN`] times the distance to its
    /// position. The robot's rate limiter still applies.
    pub(super) fn command(&self, j: usize, q_ref: &[f64; 6]) -> [f64; 6] {
        match self {
            Drive::Velocity(command) => *command,
            Drive::Servo(setpoints) => {
                let s = &setpoints[j];
                std::array::from_fn(|i| s.velocity[i] + SERVO_GAIN * (s.position[i] - q_ref[i]))
            }
        }
    }

    /// The gripper command of substep `j`, if this drive sets one per substep.
    pub(super) fn gripper(&self, j: usize) -> Option<f64> {
        match self {
            Drive::Velocity(_) => None,
            Drive::Servo(setpoints) => Some(setpoints[j].gripper),
        }
    }
}

impl GraspEnv {
    /// One env step that tracks a joint stream, as a controller's servo mode does: one
    /// [`ServoSetpoint`] per physics substep (`physics.substeps` of them). The arm's rate limiter
    /// (FR3 velocity limits, `arm.max_acceleration`) still applies, so a setpoint it cannot
    /// follow is reached late, never jumped to. Every such step runs physics (no free-space
    /// shortcut). Judged, observed and recorded like [`GraspEnv::step`].
    pub fn step_servo(&mut self, setpoints: &[ServoSetpoint]) -> Result<Step, EnvError> {
        if self.done {
            return Err(EnvError::EpisodeOver);
        }
        let expected = self.config.physics.substeps;
        if setpoints.len() != expected {
            let got = setpoints.len();
            return Err(EnvError::SetpointCount { expected, got });
        }
        for (substep, s) in setpoints.iter().enumerate() {
            let what = if s.position.iter().any(|v| !v.is_finite()) {
                format!("position {:?}", s.position)
            } else if s.velocity.iter().any(|v| !v.is_finite()) {
                format!("velocity {:?}", s.velocity)
            } else if !s.gripper.is_finite() {
                format!("gripper {}", s.gripper)
            } else {
                continue;
            };
            return Err(EnvError::NonFiniteSetpoint { substep, what });
        }
        self.scenario_events_before_step();
        self.advance(Drive::Servo(setpoints))
    }

    /// The task's judgement of a step that ended in `state`, with the contact scan's
    /// `collision` and the protective `stop` if one tripped (then always terminated); with
    /// `task.collision_voids_success`, a success after an earlier collision is that failure.
    pub(super) fn judge_step(
        &mut self,
        state: &TaskState,
        collision: Option<Failure>,
        stop: Option<Failure>,
    ) -> Judgement {
        let task = &self.config.task;
        let judgement = match stop {
            Some(stop) => judge_protective_stop(state, collision, stop, task),
            None => judge(state, collision, task),
        };
        void_success_after_collision(judgement, &mut self.first_collision, state, task)
    }

    /// Takes the step into the episode's tracker; on the terminal step (`self.done`), puts the
    /// episode's record into `info`.
    pub(super) fn track(&mut self, obs: &Observation, reward: f64, info: &mut Info) {
        self.tracker.observe(StepFacts {
            pad_contact: obs.pad_contact,
            object_z: self.object_in_base().xyz()[2],
            gripper_opening: obs.gripper_opening,
            reward,
        });
        if self.done {
            let (seed, object_xy) = self
                .scenario
                .map_or((0, [0.0; 2]), |s| (s.seed, s.object_xy));
            info.episode = Some(self.tracker.finish(Ending {
                seed,
                object_xy,
                steps: self.steps,
                success: info.success,
                failure: info.failure.as_ref(),
                physics_fault: info.physics_fault.is_some(),
            }));
        }
    }

    /// A free-space step ([`FreeSpace`]) if the config allows it, the arm is the servo arm, the
    /// object rests and the previous step found no collision; `None` when the step must run
    /// physics (the robot is then unchanged).
    pub(super) fn free_step(&mut self, command: &[f64; 6]) -> Option<ContactReport> {
        let allowed = self.config.physics.free_space
            && self.robot.kind == ArmSimulation::Servo
            && self.contacts.collision.is_none()
            && self.sim.object_at_rest(REST_SPEED, REST_TURN_RATE);
        if !allowed {
            return None;
        }
        let report = self.free_space.try_step(
            &mut self.robot,
            &self.sim.object_pose(),
            command,
            self.config.physics.dt,
            self.config.physics.substeps,
        )?;
        self.sim_in_sync = false;
        Some(report)
    }

    /// What the contacts say after a step that ran physics (or the reset): the narrow phase's
    /// report and, for the servo arm, the pairs rapier leaves out (links and palm against each
    /// other and the table) checked on the exact shapes; the deeper collision is the one
    /// reported.
    pub(super) fn simulated_contacts(&mut self) -> ContactReport {
        let mut report = self.sim.contacts();
        if self.robot.kind == ArmSimulation::Servo
            && let Some(found) = self.free_space.kinematic_collision(&self.robot)
            && report.collision.is_none_or(|(_, _, depth)| found.2 > depth)
        {
            report.collision = Some(found);
        }
        report
    }

    /// Checks an action and hands it to the robot: returns the joint-velocity command \[rad/s\]
    /// (from joint velocities, or from the TCP command through the Jacobian in `tcp` mode).
    pub(super) fn apply_action(&mut self, action: &Action) -> Result<[f64; 6], EnvError> {
        if let Some((index, &value)) = action.0.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(EnvError::NonFiniteAction { index, value });
        }
        let clipped = action.0.map(|v| v.clamp(-1.0, 1.0));
        let arm = &self.config.arm;
        let (qd, gripper) = match &self.task_space {
            None => (
                std::array::from_fn(|i| clipped[i] * arm.action_scale),
                clipped[6],
            ),
            Some(task_space) => task_space.joint_command(&self.robot.q, &clipped),
        };
        self.robot.gripper_command = gripper;
        Ok(qd)
    }

    /// The facts the task judges, in `world` \[m\].
    pub(super) fn task_state(&self, contacts: &ContactReport) -> TaskState {
        let object = self.sim.object_pose().translation.vector;
        let tcp = self.robot.tcp_in_world().xyz();
        let base_xy = self.cell.mount.base_in_world.xyz();
        TaskState {
            object: [object.x, object.y, object.z],
            object_rest_z: self.object_rest_z,
            tcp,
            pad_contact: contacts.pad_contact,
            gripper_opening: self.robot.gripper_opening(),
            object_size: self.config.scene.cube_size,
            table_height: self.config.scene.table_height,
            object_xy_from_table_centre: [object.x - base_xy[0], object.y - base_xy[1]],
            table_half_size: self.config.scene.table_size.map(|s| s / 2.0),
            place: self.place_facts(),
        }
    }

    /// The place task's facts about the cube and the fixture (`None` for the lift task), world.
    pub(super) fn place_facts(&self) -> Option<crate::task::place::PlaceFacts> {
        let fixture = self.sim.fixture_pose()?;
        let cube = self.sim.object_pose();
        let offset =
            fixture.inverse_transform_point(&nalgebra::Point3::from(cube.translation.vector));
        // The cube's face normals; the one nearest the vertical says how far it leans.
        let r = cube.rotation.to_rotation_matrix();
        let upright = (0..3).map(|i| r[(2, i)].abs()).fold(0.0, f64::max);
        let h = 0.5 * self.config.scene.cube_size;
        let lowest = (0..8)
            .map(|k| {
                let corner = nalgebra::Vector3::new(
                    if k & 1 == 0 { -h } else { h },
                    if k & 2 == 0 { -h } else { h },
                    if k & 4 == 0 { -h } else { h },
                );
                (cube * nalgebra::Point3::from(corner)).z
            })
            .fold(f64::INFINITY, f64::min);
        let f = fixture.translation.vector;
        Some(crate::task::place::PlaceFacts {
            offset_in_fixture: [offset.x, offset.y],
            bottom_above_table: lowest - self.config.scene.table_height,
            tilt: upright.clamp(-1.0, 1.0).acos(),
            fixture: [f.x, f.y, f.z],
        })
    }

    /// The observation: the robot's state and the object as the perception model reports it,
    /// in `base_link`.
    pub(super) fn observe(
        &self,
        joint_velocities: [f64; 6],
        contacts: &ContactReport,
    ) -> Observation {
        let tcp = self.robot.tcp_in_base().xyz();
        let truth = self.object_in_base();
        let seen = observe_object(&self.cell.mount, &truth, self.scenario.as_ref());
        let wrist = self.config.randomization.wrist_camera.as_ref();
        let wrist_camera = wrist_view(wrist, &self.cell.mount, &truth, tcp);
        let fixture = self.observed_fixture();
        let wrist_force = fixture.is_some().then(|| self.wrist_force(contacts));
        Observation {
            joints: self.robot.q,
            joint_velocities,
            object_rel_tcp: [0, 1, 2].map(|i| seen.position[i] - tcp[i]),
            gripper_opening: self.robot.gripper_opening(),
            object_yaw: seen.yaw,
            tcp_position: tcp,
            pad_contact: contacts.pad_contact,
            wrist_camera,
            fixture,
            wrist_force,
        }
    }

    /// The wrist force/torque sensor's reading in `base_link` \[N\] ([`Observation::wrist_force`]):
    /// zero when the step ran no physics (the simulator's contacts are then stale).
    fn wrist_force(&self, contacts: &ContactReport) -> [f64; 3] {
        if !self.sim_in_sync {
            return [0.0; 3];
        }
        let holding = contacts.pad_contact[0] && contacts.pad_contact[1];
        let world = self.sim.wrist_load(holding);
        self.cell
            .mount
            .base_in_world
            .inverse()
            .transform_vector(world)
    }

    /// The fixture as the cell knows it: its true pose moved by the scenario's error
    /// (`task.place.observed_*_noise`), in `base_link`; `None` without a fixture.
    fn observed_fixture(&self) -> Option<crate::scenario::perception::ObservedObject> {
        let truth = self.fixture_in_base()?;
        let seen = crate::scenario::perception::true_object(&self.cell.mount, &truth);
        let Some(f) = self.scenario.as_ref().and_then(|s| s.fixture) else {
            return Some(seen);
        };
        let e = &f.observed_xy_error;
        let error = self
            .cell
            .mount
            .table_in_base
            .transform_vector([e[0], e[1], 0.0]);
        Some(crate::scenario::perception::ObservedObject {
            position: [0, 1, 2].map(|i| seen.position[i] + error[i]),
            yaw: seen.yaw + f.observed_yaw_error,
        })
    }

    /// The fixture's true pose in `base_link` (its origin: the pocket's centre on the table
    /// top), if the task has one.
    pub fn fixture_in_base(&self) -> Option<fairgrasp_kinematics::Pose> {
        let fixture = self.sim.fixture_pose()?;
        Some(fairgrasp_kinematics::Pose {
            iso: self.cell.mount.base_in_world.iso.inverse() * fixture,
        })
    }
}

/// The collision between parts `a` and `b`, named in one order whatever found it (the narrow
/// phase, the exact shapes or the protective stop): the table first, then the arm from its base
/// out, the gripper last (the order of [`Part`]).
pub(super) fn collision_failure(model: &ArmModel, a: Part, b: Part) -> Failure {
    let (first, second) = if a <= b { (a, b) } else { (b, a) };
    Failure::Collision(
        first.name(model).to_string(),
        second.name(model).to_string(),
    )
}
