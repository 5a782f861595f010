//! Per-episode scenarios: object position, yaw, friction, mass and joint noise, drawn from a seed,
//! each one checked to admit a top-down grasp within the FR3's joint limits ([`sample`],
//! [`graspable`], the one Gaussian draw in [`noise`]), the curriculum that widens them
//! ([`curriculum`]), and what a policy observes of them ([`perception`]).
//!
//! A scenario family (an imperfection of a real cell, set in `[randomization]`) is a folder with
//! its settings and their rules, its draw and its effect on the step or the observation:
//! [`nudge`] (a push of the cube), [`camera_offset`] (a miscalibrated camera), [`wrist_camera`]
//! (a camera on the wrist), [`perception_noise`] (an error on the observed cube).
//! The place task's fixture is a folder too, [`fixture`]: its pose and contact conditions drawn
//! per scenario (its settings and their rules are `[task.place]`'s, in [`crate::config`]); the
//! cube is turned in the grip by [`grip_tilt`]; [`error_mix`] gives each scenario of a place
//! cell one family's error, unlabelled.

pub mod camera_offset;
pub mod curriculum;
pub mod error_mix;
pub mod fixture;
pub mod graspable;
pub mod grip_tilt;
pub mod noise;
pub mod nudge;
pub mod perception;
pub mod perception_noise;
pub mod sample;
pub mod wrist_camera;

pub use graspable::*;
pub use sample::*;
