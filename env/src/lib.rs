//! fairgrasp-env: the FR3 grasping environment in rapier3d: a robot, a task and a scenario,
//! composed by [`TaskEnv`] over a simulator facade.
//!
//! - [`robot`]: the arm (servo or multibody) and its gripper; applies an action, reports joint
//!   and gripper state.
//! - [`task`]: success, failure and reward (the lift and the place task) as pure functions of
//!   the state, and the episode's record.
//! - [`scenario`]: what is true this episode, drawn from a seed (the cube, the place task's
//!   fixture, the curriculum, the imperfection families), and what a policy observes of it.
//! - [`cell`]: which arm, where it stands (the base and the table frame in the world) and how it
//!   is simulated.
//! - [`sim`]: the facade that alone touches rapier (the world, its contacts, the exact shapes
//!   used for checks without rapier).
//! - [`mod@env`]: [`TaskEnv`] itself: the observation, the action and observation spaces, the
//!   step, the free-space steps that skip rapier.
//! - [`episode`]: the [`Policy`](episode::Policy) trait, the evaluation loop, lockstep runs and
//!   the recorded trajectory.
//! - [`sensor`]: the six-axis wrist sensor's wrench, its centre of pressure and its noise.
//! - [`mod@vec`]: N environments stepped in parallel threads, with auto-reset.
//! - [`config`]: the settings, loaded from TOML and checked with messages that name the field,
//!   and the named presets.

pub mod cell;
pub mod config;
pub mod env;
pub mod episode;
pub mod robot;
pub mod scenario;
pub mod sensor;
pub mod sim;
pub mod task;
pub mod vec;

pub use cell::mount::Mount;
pub use config::{ArmSimulation, ConfigError, EnvConfig, HOME_JOINTS, TaskKind};
pub use env::obs::Observation;
pub use env::{Action, EnvError, Info, ServoSetpoint, Step, TaskEnv};

/// The old name of [`TaskEnv`] (it runs every task: lift, place, stack), kept for one release.
#[deprecated(
    note = "renamed `TaskEnv` (it runs every task); the old name goes in the next release"
)]
pub type GraspEnv = TaskEnv;
