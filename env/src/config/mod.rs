//! The environment's configuration: plain serde data with defaults ([`env_config`], the task's
//! settings in [`task`], the rewards' weights in [`reward`]), loaded from TOML and checked with
//! messages that name the field ([`validate`], and `validate_families`, which calls each
//! scenario family's rules; all written with `check`; [`numbers`], [`error`]; every list read
//! whole, [`lists`]), the named presets
//! ([`presets`]), and where a key is written in a TOML text ([`toml_lines`]).
//!
//! A task's or a scenario family's own settings live in its folder (`settings.rs`, plain data
//! and its rules: the place task's `[task.place]` in `env/src/task/place/settings.rs`, a
//! family's in `env/src/scenario/<family>/settings.rs`) and are named here only as the type of
//! their field; those files belong to this layer too.
//!
//! Otherwise a leaf: nothing here imports the env's behaviour (no cell, sim, robot, a task's
//! rules, a family's draw or hook, or env), so every other room may import it.
//!
//! Frames: `world` is z-up with the table top at `scene.table_height`; the arm's `base_link` sits
//! at `arm.base_xyz` / `arm.base_rpy` in the world. Units: metres, radians, kilograms, seconds.

pub(crate) mod check;
pub mod env_config;
pub mod error;
pub mod lists;
pub mod numbers;
pub mod presets;
pub mod range;
pub mod reward;
pub mod sensor;
pub mod task;
pub mod toml_lines;
pub mod validate;
mod validate_families;

pub use crate::task::place::settings::{
    PlaceConfig, SEARCH_BOUNDS, SearchBound, SearchParams, SquareParams, SwitchParams,
};
pub use check::{Bounds, MAX_TABLE_RADIUS, RangeBounds, SettingNumber, bounds_rule, check_in};
pub use env_config::*;
pub use error::ConfigError;
pub use range::Range;
pub use task::TaskKind;
