//! The lift task's controls: grasp the cube and lift it.
//!
//! - [`script`]: [`ScriptedGrasp`](script::ScriptedGrasp), the open-loop script (approach →
//!   descend → close → lift → hold, planned once from the first observation); the place and
//!   stack scripts grasp with it before they carry;
//! - [`closed_loop`]: the closed-loop script (re-plans, retries a missed grasp) and the oracle
//!   (the same on the true cube pose);
//! - [`calibrated`]: the open-loop script after a (simulated) camera calibration, the
//!   engineer's fix for a miscalibrated cell;
//! - [`tuned_grip`]: the open-loop script with the grip force an engineer tuned for the cell;
//! - [`residual`]: what a residual policy corrects the script through, and the hand-written
//!   oracle residual;
//! - `controls`: the task's rows of the table of controls ([`crate::controls::CONTROLS`]).
//!
//! Shared with the other tasks and not here: the grasp poses ([`crate::grasp`]), the scripted
//! grasp's phases ([`crate::phase`]), motions ([`crate::motion`]) and the task-space
//! correction ([`crate::correction`]).

pub mod calibrated;
pub mod closed_loop;
pub(crate) mod controls;
pub mod residual;
pub mod script;
pub mod tuned_grip;
