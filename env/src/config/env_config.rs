//! The environment's configuration: serde structs with defaults, loadable from TOML, checked at
//! construction with messages that name the field.
//!
//! Frames: `world` is z-up with the table top at `scene.table_height`; the arm's `base_link` sits
//! at `arm.base_xyz` / `arm.base_rpy` in the world. Units: metres, radians, kilograms, seconds.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::config::range::Range;
pub use crate::config::sensor::{SensorConfig, WrenchSensorConfig};
pub use crate::config::task::{DEFAULT_PROTECTIVE_STOP_FORCE, RewardKind, TaskConfig};

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
    /// The cell's sensors beyond the joints and cameras (`[sensor.wrench]`).
    #[serde(skip_serializing_if = "SensorConfig::is_default")]
    pub sensor: SensorConfig,
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
    /// How each control's settings in this config were tuned, by the control's command-line
    /// name (`[control.tuned.force_search]`, written by `fairgrasp tune` into its fragment);
    /// a control without an entry runs the preset's own settings.
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub tuned: BTreeMap<String, TuningNote>,
}

impl ControlConfig {
    /// Nothing tuned (the section is left out of a written config).
    pub fn is_untuned(&self) -> bool {
        self.grip_force.is_none() && self.tuned.is_empty()
    }
}

/// How a control's settings were tuned (`fairgrasp tune`): what a comparison states beside it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TuningNote {
    /// The preset it was tuned on.
    pub preset: String,
    /// The optimiser and its library.
    pub optimiser: String,
    /// What was maximised (`success within the takt`, `success`).
    pub objective: String,
    /// Env steps the tuning spent, over all its trials.
    pub env_steps: u64,
    /// Trials, episodes per trial and the scenario seed they were drawn from (training
    /// scenarios: never a set results are reported on).
    pub trials: usize,
    pub episodes_per_trial: usize,
    pub scenario_seed: u64,
    /// The best trial's objective on those scenarios (a fraction).
    pub best: f64,
}

impl TuningNote {
    /// One line: `CMA-ES (cmaes 0.2.2), 96 trials × 150 episodes of seed 11, 3.01 M env steps`.
    pub fn summary(&self) -> String {
        format!(
            "{}, {} trials × {} episodes of seed {}, {:.2} M env steps",
            self.optimiser,
            self.trials,
            self.episodes_per_trial,
            self.scenario_seed,
            self.env_steps as f64 / 1e6
        )
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
    /// See [`crate::scenario::camera_offset::CameraOffset`].
    pub camera_offset: Option<crate::scenario::camera_offset::CameraOffset>,
    /// A push of the cube during the approach, drawn per scenario (None = never).
    /// See [`crate::scenario::nudge::NudgeConfig`].
    pub nudge: Option<crate::scenario::nudge::NudgeConfig>,
    /// A wrist camera that sees the cube exactly once the TCP is near it (None = no wrist
    /// camera). See [`crate::scenario::wrist_camera::WristCamera`].
    pub wrist_camera: Option<crate::scenario::wrist_camera::WristCamera>,
}

impl Default for RandomizationConfig {
    /// Nothing randomised; the sector is the `sector` preset's, ready to switch on.
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
    pub fn sector() -> Self {
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
            ..Self::sector()
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
