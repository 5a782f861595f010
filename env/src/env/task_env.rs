//! `TaskEnv`: the gym-style interface. `reset(seed)` and `step(&Action)`.
//!
//! An action is 6 joint-velocity commands and 1 gripper command, each in [-1, 1]: joints move at
//! `action · arm.action_scale` rad/s (or, with `arm.action_space = "tcp"`, entries 0–3 are the
//! TCP's velocity and yaw rate, see [`crate::robot::tcp_action`]); the gripper closes toward travel
//! `(g + 1)/2 · 42.5 mm` (−1 open, +1 closed) with a limited force. `terminated` means success
//! or failure, `truncated` the time limit or a physics fault; never both.
//!
//! This file reads in the order of an episode: building the env, the reset, then
//! [`TaskEnv::step`] and each part it calls in the order it calls them (the scenario's events,
//! the action, the arm's motion in free space or physics, the contacts, the observation, the
//! task's judgement, the episode's record), then what the env lets a caller read.

use crate::cell::derived::Cell;
use crate::cell::mount::Mount;
use crate::config::{ActionSpace, ArmSimulation, EnvConfig, WrenchSensorConfig};
use crate::env::drive::{Drive, check_setpoints};
use crate::env::free_space::{FreeSpace, REST_SPEED, REST_TURN_RATE};
use crate::env::obs::Observation;
pub use crate::env::step::{Action, EnvError, Info, ServoSetpoint, Step};
use crate::env::task_facts::{collision_failure, place_facts};
use crate::robot::Robot;
use crate::robot::tcp_action::TaskSpaceAction;
use crate::scenario::Scenario;
use crate::scenario::grip_tilt::{GripTiltEvent, GripTiltHook, HandState};
use crate::scenario::nudge::{NudgeEvent, NudgeHook};
use crate::scenario::perception::{observe_fixture, observe_object};
use crate::scenario::wrist_camera::wrist_view;
use crate::sensor::{Wrench, read_with_noise};
use crate::sim::Sim;
use crate::sim::contacts::{ContactReport, PairKind, TouchingPair};
use crate::sim::part::Part;
use crate::task::episode::{Ending, EpisodeTracker, StepFacts};
use crate::task::state::TaskState;
use crate::task::{Failure, Judgement, judge, judge_protective_stop, void_success_after_collision};
use fairgrasp_kinematics::{ArmModel, Pose};
use nalgebra::Isometry3;
use rapier3d::prelude::PhysicsWorld;

use crate::sim::scene::SceneHandles;

/// Physics substeps run at reset so the object settles on the table.
const SETTLE_SUBSTEPS: usize = 24;

/// The FR3 grasping environment: the robot, the task and the episode's scenario, composed over
/// the simulator facade.
pub struct TaskEnv {
    config: EnvConfig,
    /// Which arm, mounted how, simulated how.
    cell: Cell,
    /// The task-space action (`arm.action_space = "tcp"`), None in joint mode.
    task_space: Option<TaskSpaceAction>,
    sim: Sim,
    robot: Robot,
    free_space: FreeSpace,
    /// The simulator's bodies are where the robot is (false after free-space steps).
    sim_in_sync: bool,
    /// What the latest step (or reset) found touching.
    contacts: ContactReport,
    object_rest_z: f64,
    /// What this episode has shown so far (its record at the terminal step).
    tracker: EpisodeTracker,
    steps: usize,
    done: bool,
    /// This episode's first collision (`task.collision_voids_success`).
    first_collision: Option<Failure>,
    scenario: Option<Scenario>,
    /// This episode's push of the cube (the `nudged` family).
    nudge: NudgeHook,
    /// This episode's turn of the cube in the grip (the place task's `grip_tilt`).
    grip_tilt: GripTiltHook,
    /// The six-axis wrist sensor's noise, on a task with a fixture (`EnvConfig::wrench_sensor`).
    wrist_sensor: Option<WrenchSensorConfig>,
}

impl TaskEnv {
    /// Builds the world once (validating the config); call [`TaskEnv::reset`] before stepping.
    pub fn new(config: EnvConfig) -> Result<Self, EnvError> {
        config.validate()?;
        let cell = Cell::from_config(&config);
        let sim = Self::build_sim(&config, &cell.model, &cell.mount);
        Ok(Self {
            free_space: FreeSpace::new(&config, &cell.model),
            wrist_sensor: config.wrench_sensor(),
            robot: Robot::new(&config, cell.model.clone(), cell.mount.base_in_world),
            sim_in_sync: true,
            contacts: ContactReport::default(),
            task_space: (config.arm.action_space == ActionSpace::Tcp)
                .then(|| TaskSpaceAction::new(&cell, &config.arm)),
            config,
            cell,
            sim,
            object_rest_z: 0.0,
            tracker: EpisodeTracker::default(),
            steps: 0,
            done: true,
            first_collision: None,
            scenario: None,
            nudge: NudgeHook::default(),
            grip_tilt: GripTiltHook::default(),
        })
    }

    fn build_sim(config: &EnvConfig, model: &ArmModel, mount: &Mount) -> Sim {
        let cube_world = Self::spawn_pose_in_world(config, mount, config.scene.cube_xy, 0.0);
        let base = &mount.base_in_world;
        Sim::build(config, model, base, &config.arm.home_joints, &cube_world)
    }

    /// Where a cube resting at `xy` \[m\], `yaw` \[rad\] (table frame) spawns in the world: 1 mm
    /// above the table top, along the world vertical, so that it settles onto it.
    fn spawn_pose_in_world(
        config: &EnvConfig,
        mount: &Mount,
        xy: [f64; 2],
        yaw: f64,
    ) -> Isometry3<f64> {
        let resting = mount.resting_object_in_base(xy, yaw, config.scene.cube_size);
        Isometry3::translation(0.0, 0.0, 0.001) * mount.base_in_world.iso * resting.iso
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
        &self.cell.model
    }

    /// `base_link` in the world.
    pub fn base_in_world(&self) -> &Pose {
        &self.cell.mount.base_in_world
    }

    /// The arm's mount: the base and the table frame in the world and in `base_link`.
    pub fn mount(&self) -> &Mount {
        &self.cell.mount
    }

    /// The cell: arm model, mount and arm simulation.
    pub fn cell(&self) -> &Cell {
        &self.cell
    }

    /// The scenario of the current episode (`None` before the first reset).
    pub fn scenario(&self) -> Option<&Scenario> {
        self.scenario.as_ref()
    }

    /// What became of this episode's push of the cube, if the scenario has one and its step has
    /// come ([`crate::scenario::nudge::Nudge`]).
    pub fn nudge_event(&self) -> Option<NudgeEvent> {
        self.nudge.event()
    }

    /// This episode's turn of the cube in the grip, once it has happened (the place task's
    /// `task.place.grip_tilt`).
    pub fn grip_tilt_event(&self) -> Option<GripTiltEvent> {
        self.grip_tilt.event()
    }

    /// Soft reset to the scenario drawn from `seed`.
    pub fn reset(&mut self, seed: u64) -> Result<(Observation, Info), EnvError> {
        let scenario = Scenario::sample_in(&self.cell, &self.config, seed)?;
        Ok(self.reset_to(&scenario))
    }

    /// Hard reset: rebuilds the world from nothing, then resets to the scenario of `seed`.
    pub fn hard_reset(&mut self, seed: u64) -> Result<(Observation, Info), EnvError> {
        self.sim = Self::build_sim(&self.config, &self.cell.model, &self.cell.mount);
        self.reset(seed)
    }

    /// Soft reset to a given scenario: restores the built world, then places the arm, fingers
    /// and object and lets the object settle.
    pub fn reset_to(&mut self, scenario: &Scenario) -> (Observation, Info) {
        self.sim.restore();
        let object = Self::spawn_pose_in_world(
            &self.config,
            &self.cell.mount,
            scenario.object_xy,
            scenario.object_yaw,
        );
        self.sim
            .place_object(&object, scenario.friction, scenario.mass);
        if let Some(f) = &scenario.fixture {
            let on_table = Pose::from_xyz_rpy([f.xy[0], f.xy[1], 0.0], [0.0, 0.0, f.yaw]);
            let in_world = self.cell.mount.table_in_world.iso * on_table.iso;
            self.sim.place_fixture(&in_world);
            let table = self.config.scene.table_friction;
            self.sim.set_fixture_friction(f.friction.unwrap_or(table));
        }
        self.robot.teleport(&mut self.sim, &scenario.start_joints);
        self.robot.set_grip_force(self.config.gripper.force);
        for _ in 0..SETTLE_SUBSTEPS {
            self.physics_substep(&[0.0; 6]);
        }
        self.sim_in_sync = true;
        self.object_rest_z = self.sim.object_pose().translation.z;
        let rest_in_base = self.object_in_base().xyz()[2];
        self.tracker = EpisodeTracker::start(rest_in_base, self.config.scene.cube_size);
        self.steps = 0;
        self.done = false;
        self.first_collision = None;
        self.scenario = Some(*scenario);
        self.nudge.reset();
        self.grip_tilt.reset();
        let info = Info {
            scenario: Some(*scenario),
            simulated: true,
            ..Info::default()
        };
        self.contacts = self.simulated_contacts();
        (self.observe([0.0; 6], &self.contacts), info)
    }

    /// Applies one action for `physics.substeps` physics steps.
    pub fn step(&mut self, action: &Action) -> Result<Step, EnvError> {
        if self.done {
            return Err(EnvError::EpisodeOver);
        }
        self.scenario_events_before_step();
        let command = self.apply_action(action)?;
        self.advance(Drive::Velocity(command))
    }

    /// One env step that tracks a joint stream, as a controller's servo mode does: one
    /// [`ServoSetpoint`] per physics substep (`physics.substeps` of them). The arm's rate limiter
    /// (FR3 velocity limits, `arm.max_acceleration`) still applies, so a setpoint it cannot
    /// follow is reached late, never jumped to. Every such step runs physics (no free-space
    /// shortcut). Judged, observed and recorded like [`TaskEnv::step`].
    pub fn step_servo(&mut self, setpoints: &[ServoSetpoint]) -> Result<Step, EnvError> {
        if self.done {
            return Err(EnvError::EpisodeOver);
        }
        check_setpoints(setpoints, self.config.physics.substeps)?;
        self.scenario_events_before_step();
        self.advance(Drive::Servo(setpoints))
    }

    /// What the scenario does to the cube before a step's action, whatever drives the arm: the
    /// `nudged` family's push, the place task's turn in the grip.
    fn scenario_events_before_step(&mut self) {
        self.push_if_due();
        self.tilt_if_due();
    }

    /// The nudge of the `nudged` family, if this step is the one it pushes before.
    fn push_if_due(&mut self) {
        let tcp = self.robot.tcp_in_world().xyz();
        let (scenario, mount) = (self.scenario.as_ref(), &self.cell.mount);
        (self.nudge).before_step(self.steps, scenario, mount, &mut self.sim, tcp);
    }

    /// The turn of the cube in the grip (the place task's `grip_tilt`), if it is due.
    fn tilt_if_due(&mut self) {
        let drawn = self
            .scenario
            .and_then(|s| s.fixture)
            .map_or(0.0, |f| f.grip_tilt);
        if drawn == 0.0 || self.grip_tilt.event().is_some() {
            return; // nothing to turn: skip the per-step facts
        }
        let Some(facts) = place_facts(&self.sim, &self.config.scene) else {
            return;
        };
        let tcp = self.robot.tcp_in_world();
        let x = tcp.iso.rotation * nalgebra::Vector3::x();
        let hand = HandState {
            tcp: tcp.xyz(),
            tcp_x: [x.x, x.y, x.z],
            held: self.contacts.pad_contact.iter().all(|&p| p),
            cube_bottom_above_table: facts.bottom_above_table,
        };
        let scenario = self.scenario.as_ref();
        (self.grip_tilt).before_step(self.steps, scenario, &hand, &mut self.sim);
    }

    /// Checks an action and hands it to the robot: returns the joint-velocity command \[rad/s\]
    /// (from joint velocities, or from the TCP command through the Jacobian in `tcp` mode).
    fn apply_action(&mut self, action: &Action) -> Result<[f64; 6], EnvError> {
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

    /// Moves the robot for one env step (`physics.substeps` physics steps) as `drive` says, then
    /// judges, observes and records the step.
    fn advance(&mut self, drive: Drive<'_>) -> Result<Step, EnvError> {
        let q_before = self.robot.q;
        let (free, stop) = self.move_robot(drive);
        self.steps += 1;
        let info = Info {
            step: self.steps,
            scenario: self.scenario,
            simulated: free.is_none(),
            ..Info::default()
        };
        if let Some(fault) = self.sim.fault().or_else(|| self.robot.fault()) {
            return Ok(self.end_on_fault(fault, info));
        }
        // One contact report serves the observation and the collision check.
        let contacts = match free {
            Some(free) => free,
            None => self.simulated_contacts(),
        };
        self.contacts = contacts.clone();
        let env_dt = self.config.physics.dt * self.config.physics.substeps as f64;
        let velocities = std::array::from_fn(|i| (self.robot.q[i] - q_before[i]) / env_dt);
        let obs = self.observe(velocities, &contacts);
        Ok(self.judged_step(obs, &contacts, stop, info))
    }

    /// Moves the arm for one env step: a free-space step when one is allowed (its contact
    /// report returned), else `physics.substeps` physics steps with the protective stop watched
    /// after each; a stop halts the arm at once and is returned.
    fn move_robot(&mut self, drive: Drive<'_>) -> (Option<ContactReport>, Option<Failure>) {
        if let Drive::Velocity(command) = drive
            && let Some(free) = self.free_step(&command)
        {
            return (Some(free), None);
        }
        if !self.sim_in_sync {
            self.robot.hand_over(&mut self.sim, self.config.physics.dt);
            self.sim_in_sync = true;
        }
        let stop = (0..self.config.physics.substeps).find_map(|j| {
            let command = drive.command(j, &self.robot.q_ref);
            if let Some(gripper) = drive.gripper(j) {
                self.robot.gripper_command = gripper.clamp(-1.0, 1.0);
            }
            self.physics_substep(&command)
        });
        (None, stop)
    }

    /// A free-space step ([`FreeSpace`]) if the config allows it, the arm is the servo arm, the
    /// object rests and the previous step found no collision; `None` when the step must run
    /// physics (the robot is then unchanged).
    fn free_step(&mut self, command: &[f64; 6]) -> Option<ContactReport> {
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

    /// One physics step; returns why the robot stopped if a robot contact with the cube or the
    /// table pushed harder than `task.protective_stop_force` \[N\] in it: a protective stop, or,
    /// on the table, the collision that any robot–table touch is.
    fn physics_substep(&mut self, joint_command: &[f64; 6]) -> Option<Failure> {
        self.robot
            .substep(&mut self.sim, joint_command, self.config.physics.dt);
        self.sim.step();
        self.robot.sync(&self.sim);
        let contact = self.sim.strongest_robot_contact()?;
        (contact.force > self.config.task.protective_stop_force).then(|| {
            let model = &self.robot.model;
            if contact.other == Part::Table {
                collision_failure(model, contact.robot, contact.other)
            } else {
                Failure::ProtectiveStop {
                    robot_part: contact.robot.name(model).to_string(),
                    other_part: contact.other.name(model).to_string(),
                    force_n: contact.force,
                }
            }
        })
    }

    /// What the contacts say after a step that ran physics (or the reset): the narrow phase's
    /// report and, for the servo arm, the pairs rapier leaves out (links and palm against each
    /// other and the table) checked on the exact shapes; the deeper collision is the one
    /// reported.
    fn simulated_contacts(&mut self) -> ContactReport {
        let mut report = self.sim.contacts();
        if self.robot.kind == ArmSimulation::Servo
            && let Some(found) = self.free_space.kinematic_collision(&self.robot)
            && report.collision.is_none_or(|(_, _, depth)| found.2 > depth)
        {
            report.collision = Some(found);
        }
        report
    }

    /// The step a physics fault ended: truncated, unpaid, observed with no contacts, recorded.
    fn end_on_fault(&mut self, fault: String, mut info: Info) -> Step {
        self.done = true;
        info.physics_fault = Some(fault);
        let obs = self.observe([0.0; 6], &ContactReport::default());
        self.track(&obs, 0.0, &mut info);
        Step {
            obs,
            reward: 0.0,
            terminated: false,
            truncated: true,
            info,
        }
    }

    /// The step that reached `obs` with `contacts` (and the protective `stop`, if one tripped):
    /// judged by the task, truncated at `task.max_steps`, recorded.
    fn judged_step(
        &mut self,
        obs: Observation,
        contacts: &ContactReport,
        stop: Option<Failure>,
        mut info: Info,
    ) -> Step {
        let collision = contacts.collision.map(|(a, b, depth)| {
            info.collision_depth_m = Some(depth);
            collision_failure(&self.robot.model, a, b)
        });
        let state = self.task_state(contacts);
        let judgement = self.judge_step(&state, collision, stop);
        info.success = judgement.success;
        info.failure = judgement.failure;
        let truncated = !judgement.terminated && self.steps >= self.config.task.max_steps;
        self.done = judgement.terminated || truncated;
        self.track(&obs, judgement.reward, &mut info);
        Step {
            obs,
            reward: judgement.reward,
            terminated: judgement.terminated,
            truncated,
            info,
        }
    }

    /// The facts the task judges, in `world` \[m\].
    fn task_state(&self, contacts: &ContactReport) -> TaskState {
        let object = self.sim.object_pose().translation.vector;
        let tcp = self.robot.tcp_in_world().xyz();
        let base_xy = self.cell.mount.base_in_world.xyz();
        let scene = &self.config.scene;
        TaskState {
            object: [object.x, object.y, object.z],
            object_rest_z: self.object_rest_z,
            tcp,
            pad_contact: contacts.pad_contact,
            gripper_opening: self.robot.gripper_opening(),
            object_size: scene.cube_size,
            table_height: scene.table_height,
            object_xy_from_table_centre: [object.x - base_xy[0], object.y - base_xy[1]],
            table_half_size: scene.table_size.map(|s| s / 2.0),
            place: place_facts(&self.sim, scene),
        }
    }

    /// The task's judgement of a step that ended in `state`, with the contact scan's
    /// `collision` and the protective `stop` if one tripped (then always terminated); with
    /// `task.collision_voids_success`, a success after an earlier collision is that failure.
    fn judge_step(
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
    fn track(&mut self, obs: &Observation, reward: f64, info: &mut Info) {
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
                step_seconds: self.config.physics.dt * self.config.physics.substeps as f64,
                takt: self.config.task.takt(),
                success: info.success,
                failure: info.failure.as_ref(),
                physics_fault: info.physics_fault.is_some(),
            }));
        }
    }

    /// The observation: the robot's state and the object as the perception model reports it,
    /// in `base_link`.
    fn observe(&self, joint_velocities: [f64; 6], contacts: &ContactReport) -> Observation {
        let tcp = self.robot.tcp_in_base().xyz();
        let truth = self.object_in_base();
        let mount = &self.cell.mount;
        let seen = observe_object(mount, &truth, self.scenario.as_ref());
        let wrist = self.config.randomization.wrist_camera.as_ref();
        let wrist_camera = wrist_view(wrist, mount, &truth, tcp);
        let drawn = self.scenario.as_ref().and_then(|s| s.fixture);
        let fixture =
            (self.fixture_in_base()).map(|truth| observe_fixture(mount, &truth, drawn.as_ref()));
        let wrist = self.wrist_wrench(contacts);
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
            wrist_force: wrist.map(|w| w.force),
            wrist_torque: wrist.map(|w| w.torque),
        }
    }

    /// The six-axis wrist sensor's reading in `base_link` ([`Observation::wrist_force`],
    /// [`Observation::wrist_torque`]; torque about the flange), where the preset has the
    /// sensor: the true wrench of the step's last physics substep (zero when the step ran no
    /// physics: the simulator's contacts are then stale, and nothing touched) with the sensor's
    /// noise.
    fn wrist_wrench(&self, contacts: &ContactReport) -> Option<Wrench> {
        let sensor = self.wrist_sensor.as_ref()?;
        let flange = self.robot.model.fk_flange(&self.robot.q);
        let truth = if self.sim_in_sync {
            let holding = contacts.pad_contact[0] && contacts.pad_contact[1];
            let base = &self.cell.mount.base_in_world;
            let origin = base.compose(&flange).xyz();
            let world = self.sim.wrist_wrench(holding, origin, sensor.friction);
            world.in_frame(base)
        } else {
            Wrench::default()
        };
        let seed = self.scenario.as_ref().map_or(0, |s| s.seed);
        Some(read_with_noise(&truth, &flange, sensor, seed, self.steps))
    }

    /// The object pose in `base_link` (the truth, not what is observed).
    pub fn object_in_base(&self) -> Pose {
        Pose {
            iso: self.cell.mount.base_in_world.iso.inverse() * self.sim.object_pose(),
        }
    }

    /// The joints' velocity \[rad/s\] at the end of the latest step: the rate-limited command
    /// the servo arm moves at (zero after a reset).
    pub fn joint_velocities(&self) -> [f64; 6] {
        self.robot.qd
    }

    /// The gripper command in effect, −1 open … +1 closed.
    pub fn gripper_command(&self) -> f64 {
        self.robot.gripper_command
    }

    /// The TCP pose in `base_link` at the current joints.
    pub fn tcp_in_base(&self) -> Pose {
        self.robot.tcp_in_base()
    }

    /// Each finger's squeeze force in effect \[N\]: `gripper.force` after a reset.
    pub fn grip_force(&self) -> f64 {
        self.robot.grip_force()
    }

    /// Squeezes with `newtons` per finger from the next step on, until the next reset (as a
    /// real gripper takes a force with each command); finite and in (0, 100] N.
    pub fn set_grip_force(&mut self, newtons: f64) -> Result<(), EnvError> {
        if !(newtons.is_finite() && newtons > 0.0 && newtons <= 100.0) {
            return Err(EnvError::GripForce(newtons));
        }
        self.robot.set_grip_force(newtons);
        Ok(())
    }

    /// Current finger travels \[m\] (0 open … 0.0425 closed).
    pub fn finger_travel(&self) -> [f64; 2] {
        self.robot.fingers.map(|f| f.travel)
    }

    /// What the latest step (or reset) found touching: collisions, pad contacts, pad
    /// penetration (from the narrow phase and, for the servo arm's links, palm and table, the
    /// exact shapes; a free-space step uses the exact shapes alone).
    pub fn contacts(&self) -> ContactReport {
        self.contacts.clone()
    }

    /// Every touching pair, deepest first, with how it is judged: the narrow phase's as of the
    /// latest step that ran physics (or the reset) and, for the servo arm, the penetrating
    /// link, palm and table pairs rapier does not compute, from the exact shapes now.
    pub fn touching_pairs(&self) -> Vec<TouchingPair> {
        let mut pairs = self.sim.touching_pairs();
        if self.robot.kind == ArmSimulation::Servo {
            let found = self.free_space.kinematic_penetrations(&self.robot);
            pairs.extend(found.into_iter().map(|(a, b, depth)| TouchingPair {
                a,
                b,
                distance: -depth,
                kind: PairKind::Collision,
            }));
            pairs.sort_by(|x, y| x.distance.total_cmp(&y.distance));
        }
        pairs
    }

    /// The fixture's true pose in `base_link` (its origin: the pocket's centre on the table
    /// top), if the task has one.
    pub fn fixture_in_base(&self) -> Option<Pose> {
        let fixture = self.sim.fixture_pose()?;
        Some(Pose {
            iso: self.cell.mount.base_in_world.iso.inverse() * fixture,
        })
    }

    /// Current joint angles \[rad\].
    pub fn joints(&self) -> [f64; 6] {
        self.robot.q
    }

    /// Test and debugging access to the physics world.
    pub fn world_mut(&mut self) -> (&mut PhysicsWorld, &SceneHandles) {
        self.sim.world_mut()
    }
}
