//! The stack task's controls: set the held cube down squarely on a second cube standing on the
//! table.
//!
//! - `script`: the open-loop script ([`open_loop`]: the place script set down on the second
//!   cube's top), the force lower ([`force_lower`]) and the residual interface ([`residual`]);
//!   its items are this folder's, at `stack::`;
//! - `controls`: the task's rows of the table of controls ([`crate::controls::CONTROLS`]).

pub(crate) mod controls;
mod script;

pub use script::*;
