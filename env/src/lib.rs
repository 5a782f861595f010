//! fairgrasp-env: the FR3 grasping environment in rapier3d, composed of three pieces.
//!
//! - the **robot** ([`robot`]): the arm (servo or multibody) and its gripper; applies an action,
//!   reports joint and gripper state;
//! - the **task** ([`task`]): success, failure and reward as pure functions of the state;
//! - the **scenario** ([`randomize`], [`perception`], [`curriculum`]): what is true this episode
//!   (drawn from a seed) and what a policy observes of it.
//!
//! [`env`]'s `GraspEnv` composes them over [`sim`], the facade that alone touches rapier
//! ([`scene`] builds its world, [`contacts`] reads its narrow phase; [`shapes`] places the
//! same colliders analytically for checks without rapier). Frames: [`mount`] (the
//! base and the table frame, for any mount). Interface: [`obs`], [`spaces`], [`step`];
//! [`config`] and [`validate`] for settings; [`vec_env`], [`trajectory`], [`policy`] for
//! parallel stepping, episode export and evaluation.

pub mod cell;
pub mod config;
pub mod env;
pub mod episode;
pub mod robot;
pub mod scenario;
pub mod sim;
pub mod task;
pub mod vec;

pub use cell::mount::Mount;
pub use config::{ArmSimulation, ConfigError, EnvConfig, HOME_JOINTS, TaskKind};
pub use env::obs::Observation;
pub use env::{Action, EnvError, GraspEnv, Info, ServoSetpoint, Step};
