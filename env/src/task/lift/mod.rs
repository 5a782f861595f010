//! The lift task (`task.kind = "lift"`, the default): pick the cube up `task.lift_height` above
//! where it rested and hold it. Its rules are in [`rules`]; its settings are `[task]`'s
//! `lift_height` ([`crate::config::TaskConfig`]).

pub mod rules;

pub use rules::{distance_to_go, is_lifted};
