//! The environment's configuration: serde structs with defaults, loadable from TOML, checked at
//! construction with messages that name the field.
//!
//! Frames: `world` is z-up with the table top at `scene.table_height`; the arm's `base_link` sits
//! at `arm.base_xyz` / `arm.base_rpy` in the world. Units: metres, radians, kilograms, seconds.

use serde::{Deserialize, Serialize};

pub use crate::config::range::Range;

pub use fairgrasp_types::ArmSimulation;

/// The arm the env simulates: the FR3, the only arm with the mass properties and collision
/// capsules a simulation needs (see `docs/FR3.md`). Its joint limits bound `arm.home_joints`.
pub const SIMULATED_ARM: fairgrasp_kinematics::ArmKind = fairgrasp_kinematics::ArmKind::Fr3;

/// Home joints \[rad\]: the TCP 0.30 m in front of the base (+x), 0.25 m above it, pointing down.
pub const HOME_JOINTS: [f64; 6] = [
    0.3469,
    -1.3981,
    -1.4294,
    -1.8850,
    std::f64::consts::FRAC_PI_2,
    0.0,
];

/// Every setting of the environment.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct EnvConfig {
    pub physics: PhysicsConfig,
    pub arm: ArmConfig,
    pub gripper: GripperConfig,
    pub scene: SceneConfig,
    pub task: TaskConfig,
    pub randomization: RandomizationConfig,
    /// What an engineer tuned for this cell, read only by the hand-written controls.
    #[serde(skip_serializing_if = "ControlConfig::is_untuned")]
    pub control: ControlConfig,
}

/// Settings an engineer tuned for a cell, read only by the hand-written controls
/// (`fairgrasp_planner`), never by the env's physics or by a learned policy.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct ControlConfig {
    /// Squeeze per finger \[N\] of the "script + tuned grip" control, found by a grid search on
    /// training scenarios (docs/contact.md); `None`: the control squeezes `gripper.force`, as
    /// the open-loop script does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grip_force: Option<f64>,
}

impl ControlConfig {
    /// Nothing tuned (the section is left out of a written config).
    pub fn is_untuned(&self) -> bool {
        self.grip_force.is_none()
    }
}

/// Physics integration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhysicsConfig {
    /// Physics time step \[s\] (the seed's 1/240).
    pub dt: f64,
    /// Physics steps per environment step (the seed's 20).
    pub substeps: usize,
    /// Contact softness natural frequency \[Hz\]; rapier's 30 Hz lets a squeeze sink the fingers.
    pub contact_natural_frequency: f64,
    /// Solver iterations per physics step.
    pub solver_iterations: usize,
    /// Skip rigid-body simulation in env steps where nothing can touch the object (servo arm
    /// only): the links are placed by FK, the fingers follow their motor, and table and
    /// self-collisions are checked with the exact shapes. `false` simulates every step.
    pub free_space: bool,
}

impl Default for PhysicsConfig {
    fn default() -> Self {
        Self {
            dt: 1.0 / 240.0,
            substeps: 20,
            contact_natural_frequency: 120.0,
            solver_iterations: 3,
            free_space: true,
        }
    }
}

/// The arm and how actions drive it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArmConfig {
    /// `servo` (fast, default) or `multibody` (dynamic, motor-driven).
    pub model: ArmSimulation,
    /// `base_link` position in the world \[m\].
    pub base_xyz: [f64; 3],
    /// `base_link` orientation in the world, URDF roll, pitch, yaw \[rad\].
    pub base_rpy: [f64; 3],
    /// Joint angles at reset \[rad\].
    pub home_joints: [f64; 6],
    /// Joint velocity for an action of 1.0 \[rad/s\] (the seed's 0.5).
    pub action_scale: f64,
    /// Joint acceleration limit \[rad/s²\] (FAIRINO publishes none, see docs/FR3.md: fairgrasp's
    /// choice).
    pub max_acceleration: f64,
    /// What an action's first entries command: `joint` velocities (the seed's) or the `tcp`'s
    /// velocity and yaw rate in the table frame ([`crate::robot::tcp_action`]).
    pub action_space: ActionSpace,
    /// TCP speed for an action of 1.0 in `tcp` mode \[m/s\].
    pub tcp_speed: f64,
    /// Yaw rate for an action of 1.0 in `tcp` mode \[rad/s\].
    pub tcp_yaw_rate: f64,
    /// In `tcp` mode, how a command that asks a joint for more than it may give is scaled
    /// down (direction kept): to the FR3's `joint_limits` (default), or so that no joint
    /// exceeds `arm.action_scale` (`action_scale`: what the pure PPO recipe uses).
    pub tcp_saturation: TcpSaturation,
    /// How action entry 6 drives the gripper: `continuous` (the fingers close in proportion,
    /// the default) or `binary` (open below 0, closed from 0 up: the pure PPO recipe's).
    pub gripper_command: GripperCommand,
}

/// How a task-space command is scaled down when a joint would exceed its allowed rate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum TcpSaturation {
    /// Each joint's velocity limit (3.15–3.2 rad/s for the FR3).
    #[default]
    JointLimits,
    /// `arm.action_scale` for every joint (the joint action space's own bound).
    ActionScale,
}

/// How action entry 6 commands the gripper.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum GripperCommand {
    /// −1 open … +1 closed, in proportion.
    #[default]
    Continuous,
    /// Open below 0, closed from 0 up (as Isaac Lab's lift task: a half-closed gripper lands
    /// an exploring policy's fingers on the cube).
    Binary,
}

/// What the action's entries 0–5 command.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ActionSpace {
    /// Joint velocities j1 … j6 (× `arm.action_scale` rad/s).
    #[default]
    Joint,
    /// TCP velocity x, y, z (× `arm.tcp_speed`), yaw rate (× `arm.tcp_yaw_rate`), two unused.
    Tcp,
}

impl Default for ArmConfig {
    fn default() -> Self {
        Self {
            model: ArmSimulation::Servo,
            base_xyz: [0.0, 0.0, 0.6],
            base_rpy: [0.0, 0.0, 0.0],
            home_joints: HOME_JOINTS,
            action_scale: 0.5,
            max_acceleration: 10.0,
            action_space: ActionSpace::Joint,
            tcp_speed: 0.15,
            tcp_yaw_rate: 1.0,
            tcp_saturation: TcpSaturation::JointLimits,
            gripper_command: GripperCommand::Continuous,
        }
    }
}

/// The parallel gripper's drive.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GripperConfig {
    /// Squeeze force of each finger \[N\]. 5 N holds a 0.1 kg cube (μ 0.8) with 0.6 mm pad
    /// penetration; 20 N (the low end of real grippers) sinks the pads 2.2 mm at 120 Hz contacts.
    pub force: f64,
    /// Finger pad friction coefficient.
    pub pad_friction: f64,
}

impl Default for GripperConfig {
    fn default() -> Self {
        Self {
            force: 5.0,
            pad_friction: 0.8,
        }
    }
}

/// Table and object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SceneConfig {
    /// Height of the table top above world z = 0 \[m\].
    pub table_height: f64,
    /// Table top size x, y \[m\], centred on the arm base's x, y.
    pub table_size: [f64; 2],
    /// Table friction coefficient (the seed's 1.2).
    pub table_friction: f64,
    /// Cube edge length \[m\].
    pub cube_size: f64,
    /// Cube mass \[kg\].
    pub cube_mass: f64,
    /// Cube friction coefficient (the seed's 0.8).
    pub cube_friction: f64,
    /// Cube position when not randomised: x, y \[m\] on the table top in the table frame (origin
    /// under the base origin, x along the base's heading; for a level base, base x, y).
    pub cube_xy: [f64; 2],
}

impl Default for SceneConfig {
    fn default() -> Self {
        Self {
            table_height: 0.6,
            table_size: [1.2, 1.2],
            table_friction: 1.2,
            cube_size: 0.05,
            cube_mass: 0.1,
            cube_friction: 0.8,
            cube_xy: [0.35, 0.0],
        }
    }
}

/// The task, its success, reward and time limit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TaskConfig {
    /// `lift` (the default) or `place` (seat the cube in the fixture, `[task.place]`).
    #[serde(skip_serializing_if = "is_lift")]
    pub kind: crate::config::place::TaskKind,
    /// The place task's fixture and seated criterion (used when `kind = "place"`).
    #[serde(skip_serializing_if = "is_default_place")]
    pub place: crate::config::place::PlaceConfig,
    /// Steps before the episode is truncated (the seed's 200).
    pub max_steps: usize,
    /// Lift above the resting height that counts as success \[m\].
    pub lift_height: f64,
    /// Reward on success.
    pub success_reward: f64,
    /// Reward on a collision (negative).
    pub collision_reward: f64,
    /// Dense reward per metre of TCP–object distance (negative).
    pub distance_reward: f64,
    /// Does a collision end the episode?
    pub terminate_on_collision: bool,
    /// With `terminate_on_collision = false` (training), is a success after a collision earlier
    /// in the episode void? Then that step ends the episode as the collision's failure, paid
    /// the collision's reward: what an evaluation, which ends the episode at the collision,
    /// would have judged. Default false (the success counts).
    pub collision_voids_success: bool,
    /// With `terminate_on_collision = false` (training), does a self-collision (two robot parts:
    /// the arm or the gripper against itself) still end the episode? A touch of the table then
    /// goes on as before. Default false (no collision ends a training episode).
    pub terminate_on_self_collision: bool,
    /// Which reward the task pays (the evaluation's success criterion is the same for all).
    pub reward: RewardKind,
    /// Protective stop threshold \[N\]: a contact between the robot (links, palm, finger struts,
    /// pads) and the cube or the table pushing harder than this ends the episode with
    /// `protective_stop`, as a real cobot's collision detection stops the arm. Checked after
    /// every physics substep; the force is the contact pair's solver impulse over `physics.dt`.
    ///
    /// Default 35 N, from measurement, well under the published limits (ISO/TS 15066 Annex A:
    /// 140 N quasi-static for hands and fingers, 65 N for the face, the lowest region; UR's
    /// default power-and-force limit 150 N; FAIRINO states its collision levels per joint, not
    /// as a TCP force). The simulated contacts are soft: a pad pressing the cube sinks it 2 mm
    /// into the table at 46–95 N (baseline on `hard`), so 140 N would stop nothing in time.
    /// Normal baseline grasps peak at 26 N (`full`) and 27 N (`hard`): the fingers' closing
    /// impact on the cube. See README, "Protective stop".
    pub protective_stop_force: f64,
    /// Weights of the staged reward (used when `reward = "staged"`).
    pub staged: crate::config::reward::StagedReward,
}

/// The task's reward function; each is a pure function in [`crate::task`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RewardKind {
    /// The seed recipe's: `success_reward` on success, `collision_reward` on a collision, else
    /// `distance_reward · |TCP − object|`.
    #[default]
    Seed,
    /// Reach, grasp, lift shaping gated on the grasp, success; bounded per step
    /// ([`mod@crate::task::reward`], weights in `[task.staged]`).
    Staged,
}

/// Default protective stop threshold \[N\] (see [`TaskConfig::protective_stop_force`]).
pub const DEFAULT_PROTECTIVE_STOP_FORCE: f64 = 35.0;

fn is_lift(kind: &crate::config::place::TaskKind) -> bool {
    *kind == crate::config::place::TaskKind::Lift
}

fn is_default_place(place: &crate::config::place::PlaceConfig) -> bool {
    *place == crate::config::place::PlaceConfig::default()
}

impl Default for TaskConfig {
    fn default() -> Self {
        Self {
            kind: crate::config::place::TaskKind::Lift,
            place: crate::config::place::PlaceConfig::default(),
            max_steps: 200,
            lift_height: 0.03,
            success_reward: 10.0,
            collision_reward: -1.0,
            distance_reward: -0.005,
            terminate_on_collision: true,
            collision_voids_success: false,
            terminate_on_self_collision: false,
            reward: RewardKind::Seed,
            protective_stop_force: DEFAULT_PROTECTIVE_STOP_FORCE,
            staged: crate::config::reward::StagedReward::default(),
        }
    }
}

/// What is randomised at reset; each part switchable.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RandomizationConfig {
    /// Sample the object position in a sector in front of the base.
    pub position: bool,
    /// Sector radius on the table top, from the point under the base origin \[m\] (for a level
    /// base, from the joint-1 axis).
    pub radius: Range,
    /// Sector angle about the world vertical, 0 = the base's heading (base +x) \[rad\].
    pub angle: Range,
    /// Sample the object yaw in [0, 2π).
    pub yaw: bool,
    /// Sample the object friction in this range (None = the scene's value).
    pub friction: Option<Range>,
    /// Multiply the object mass by a factor in this range (None = 1).
    pub mass_scale: Option<Range>,
    /// Standard deviation of Gaussian noise on the home joints \[rad\] (0 = none).
    pub joint_noise: f64,
    /// Perception noise: a per-episode error on the *observed* object position \[m\] and yaw
    /// \[rad\] (standard deviations; 0 = exact). The physics is unaffected.
    pub observed_position_noise: f64,
    pub observed_yaw_noise: f64,
    /// A miscalibrated camera: a fixed error on every observed cube pose (None = calibrated).
    /// See [`crate::config::families::CameraOffset`].
    pub camera_offset: Option<crate::config::families::CameraOffset>,
    /// A push of the cube during the approach, drawn per scenario (None = never).
    /// See [`crate::config::families::NudgeConfig`].
    pub nudge: Option<crate::config::families::NudgeConfig>,
    /// A wrist camera that sees the cube exactly once the TCP is near it (None = no wrist
    /// camera). See [`crate::config::families::WristCamera`].
    pub wrist_camera: Option<crate::config::families::WristCamera>,
}

impl Default for RandomizationConfig {
    /// Nothing randomised; the sector is the `seed` preset's, ready to switch on.
    fn default() -> Self {
        Self {
            position: false,
            radius: [0.25, 0.35],
            angle: [-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2],
            yaw: false,
            friction: None,
            mass_scale: None,
            joint_noise: 0.0,
            observed_position_noise: 0.0,
            observed_yaw_noise: 0.0,
            camera_offset: None,
            nudge: None,
            wrist_camera: None,
        }
    }
}

impl RandomizationConfig {
    /// The seed recipe's sector, shifted out by 0.10 m: radius 0.25–0.35 m, angle ±90°, random
    /// yaw. The seed's own 0.15–0.25 m is too close to the FR3's base: there a top-down grasp
    /// folds the elbow until wrist 1 meets the upper arm (only 4 % of 10 000 samples are
    /// collision-free), while every sample from 0.25 m out is (a test checks 10 000).
    pub fn seed_sector() -> Self {
        Self {
            position: true,
            yaw: true,
            ..Self::default()
        }
    }

    /// A wider sector for harder training: radius 0.25–0.45 m (docs/FR3.md's comfortable table
    /// region), angle ±135°, random yaw; also fully graspable top-down (10 000 samples).
    pub fn wide_sector() -> Self {
        Self {
            radius: [0.25, 0.45],
            angle: [-0.75 * std::f64::consts::PI, 0.75 * std::f64::consts::PI],
            ..Self::seed_sector()
        }
    }

    /// Everything switched on: the wide sector, friction U(0.3, 1.0), mass ×U(0.8, 1.2) and
    /// N(0, 0.05 rad) joint noise.
    pub fn full() -> Self {
        Self {
            friction: Some([0.3, 1.0]),
            mass_scale: Some([0.8, 1.2]),
            joint_noise: 0.05,
            ..Self::wide_sector()
        }
    }

    /// `full` plus perception noise: 1 cm on the observed position, 10° on the observed yaw.
    pub fn hard() -> Self {
        Self {
            observed_position_noise: 0.01,
            observed_yaw_noise: 10f64.to_radians(),
            ..Self::full()
        }
    }
}
