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

pub mod bench;
pub mod config;
pub mod config_numbers;
pub mod contacts;
pub mod convert;
pub mod curriculum;
pub mod diagnostics;
pub mod env;
pub mod families;
pub mod finger_drive;
pub mod free_space;
pub mod mount;
pub mod nudge;
pub mod obs;
pub mod part;
pub mod perception;
pub mod policy;
pub mod presets;
pub mod randomize;
pub mod reward;
pub mod robot;
pub mod scene;
pub mod shapes;
pub mod sim;
mod snapshot;
pub mod soak;
pub mod spaces;
pub mod step;
pub mod task;
pub mod tcp_action;
pub mod trajectory;
pub mod validate;
pub mod vec_env;
mod vec_worker;

pub use config::{ArmModelKind, ConfigError, EnvConfig};
pub use env::{Action, EnvError, GraspEnv, Info, Step};
pub use mount::Mount;
pub use obs::Observation;

/// Home joints [rad]: the TCP 0.30 m in front of the base (+x), 0.25 m above it, pointing down.
pub const HOME_JOINTS: [f64; 6] = [
    0.3469,
    -1.3981,
    -1.4294,
    -1.8850,
    std::f64::consts::FRAC_PI_2,
    0.0,
];
