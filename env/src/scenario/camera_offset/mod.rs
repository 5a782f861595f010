//! The miscalibrated-camera family (`miscalibrated`, `miscalibrated_b`): the camera's extrinsic
//! calibration to the base is off by a fixed rigid error for the cell, so every observed cube
//! pose is the true one moved by that error. Nothing is drawn: the error is the config's, the
//! same for every episode, carried by the scenario (`Scenario::camera_offset`).
//!
//! - [`settings`]: `[randomization] camera_offset = { origin, xyz, yaw }` ([`CameraOffset`]),
//!   its bounds and rules, and the error as a transform of the table frame;
//! - applied to what a policy observes in [`crate::scenario::perception::observe_object`]
//!   (before the episode's perception noise).

pub mod settings;

pub use settings::{CameraOffset, MAX_CAMERA_SHIFT, MAX_CAMERA_YAW};
