//! The perception-noise family (`hard`): a per-episode error on the observed cube's position (on
//! the table plane) and yaw, drawn from the scenario's seed; the physics is unaffected.
//!
//! - [`settings`]: the rules of `[randomization]`'s `observed_position_noise` \[m\] and
//!   `observed_yaw_noise` \[rad\] (standard deviations; flat keys of
//!   [`crate::config::RandomizationConfig`]);
//! - [`draw`]: the scenario's errors ([`draw_perception_errors`], drawn in `Scenario::sample_in`
//!   with the cube's own generator, after the start joints);
//! - applied to what a policy observes in [`crate::scenario::perception::observe_object`], after
//!   the camera's calibration error.

pub mod draw;
pub mod settings;

pub use draw::draw_perception_errors;
pub use settings::check_perception_noise;
