//! The simulator facade: everything the env does to rapier, behind named operations.
//!
//! The robot, the task and the scenario code never touch rapier's sets; they ask this facade to
//! place the arm, drive the fingers, place the object, step, and report contacts. Poses cross
//! this boundary as f64 nalgebra isometries in `world` \[m\]; rapier's f32 types stay inside.

pub mod collision_filter;
pub mod contacts;
pub mod convert;
pub mod finger_drive;
pub mod fixture;
pub mod part;
pub mod scene;
pub mod shapes;
pub(crate) mod snapshot;
pub mod world;

pub use world::*;
