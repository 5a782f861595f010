//! The place cell's unlabelled mix of errors (`[task.place.mix]`, the `place_cell` preset):
//! each scenario carries the error of one family only — the fixture's pose known to its
//! tolerance, a grasp off the cube's centre, or the cube tilted in the grip — drawn per scenario
//! with the mix's weights; nothing observes which. Each family's size is the preset's own
//! setting of it (`task.place.observed_position_noise` / `observed_yaw_noise`,
//! `randomization.observed_position_noise` / `observed_yaw_noise`, `task.place.grip_tilt`).
//!
//! - [`settings`]: the weights and their rule ([`ErrorMix`], a field of
//!   [`crate::config::PlaceConfig`]);
//! - [`draw`]: the scenario's family ([`draw_error_family`]) and what it keeps of the drawn
//!   errors ([`keep_only`], called by [`crate::scenario::Scenario::sample`]).

pub mod draw;
pub mod settings;

pub use draw::{draw_error_family, keep_only};
pub use settings::{ErrorFamily, ErrorMix};
