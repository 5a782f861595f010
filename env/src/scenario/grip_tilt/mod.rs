//! The grip-tilt family of the place task (`place_tilted`): once per episode, when the cube is
//! first carried clear of the table, it turns in the grip about the axis between the pads by an
//! angle drawn from the scenario's seed; nothing observes it.
//!
//! - [`settings`]: the bounds and rule of `[task.place] grip_tilt` (a field of
//!   [`crate::config::PlaceConfig`]), and how high the cube must be carried ([`GRIP_TILT_LIFT`]);
//! - [`draw`]: the scenario's angle ([`draw_grip_tilt`], drawn with the fixture's contact
//!   conditions in [`crate::scenario::fixture`], kept in `FixturePose::grip_tilt`);
//! - [`hook`]: the turn carried out before a step's action ([`GripTiltHook`], called at the top
//!   of `TaskEnv::step`), and what became of it ([`GripTiltEvent`]).

pub mod draw;
pub mod hook;
pub mod settings;

pub use draw::draw_grip_tilt;
pub use hook::{GripTiltEvent, GripTiltHook, HandState};
pub use settings::{GRIP_TILT_LIFT, MAX_GRIP_TILT};
