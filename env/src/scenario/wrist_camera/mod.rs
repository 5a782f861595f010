//! The wrist-camera family (`wrist_camera`): a camera on the wrist that sees the cube exactly once
//! the TCP is near it. Nothing is drawn and nothing happens to the cube; the observation gains a
//! field ([`crate::Observation::wrist_camera`]).
//!
//! - [`settings`]: `[randomization] wrist_camera = { range }` ([`WristCamera`]) and its rule;
//! - [`view`]: what the camera sees at a step ([`wrist_view`], called by the env's observation).

pub mod settings;
pub mod view;

pub use settings::{MAX_WRIST_RANGE, WristCamera};
pub use view::wrist_view;
