//! fairgrasp-env: the FR3 grasping environment in rapier3d.
//!
//! - [`config`]: every setting, with defaults and presets; [`validate`]: TOML and checks.
//! - [`scene`]: the world built once: table, cube, arm (servo or multibody), gripper.
//! - [`arm`]: how joint-velocity commands move each arm model, and how joints are read back.
//! - [`contacts`]: collisions (with the pair named) and finger–cube contacts.
//! - [`obs`]: the observation layout, in the arm's base frame.
//! - [`task`]: success, failure and reward as pure functions of the state.
//! - [`env`]: `GraspEnv`: `reset(seed)`, `step(&Action)`; [`step`]: the values it exchanges.
//! - [`randomize`], [`curriculum`]: scenarios per seed, graspability, stages.
//! - [`vec_env`], [`trajectory`]: parallel stepping with auto-reset; episode export.

pub mod arm;
pub mod bench;
pub mod config;
pub mod contacts;
pub mod convert;
pub mod curriculum;
pub mod diagnostics;
pub mod env;
pub mod obs;
pub mod policy;
pub mod presets;
pub mod randomize;
pub mod scene;
mod snapshot;
pub mod step;
pub mod task;
pub mod trajectory;
pub mod validate;
pub mod vec_env;

pub use config::{ArmModelKind, ConfigError, EnvConfig};
pub use env::{Action, EnvError, GraspEnv, Info, Step};
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
