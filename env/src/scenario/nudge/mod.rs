//! The `nudged` family: the cube is pushed across the table once per episode, during the
//! approach, by a push drawn from the scenario's seed.
//!
//! - [`settings`]: `[randomization] nudge = { distance, step, min_tcp_distance }`
//!   ([`NudgeConfig`]) and its rules;
//! - [`draw`]: the scenario's push ([`Nudge`], drawn by [`draw_nudge`] in `Scenario::sample`);
//! - [`hook`]: the push carried out before the drawn step's action ([`NudgeHook`], called at the
//!   top of `TaskEnv::step`), and what became of it ([`NudgeEvent`]).
//!
//! Frames: the push is drawn in the table frame ([`crate::Mount`]), the event's positions are in
//! `world`.

pub mod draw;
pub mod hook;
pub mod settings;

pub use draw::{Nudge, draw_nudge};
pub use hook::{NudgeEvent, NudgeHook};
pub use settings::{MAX_NUDGE, MIN_TCP_DISTANCE, NudgeConfig};
