//! The place task's controls: set the held cube into a pocket in a fixture.
//!
//! - [`script`]: [`ScriptedPlace`], the open-loop script (the lift task's scripted grasp, then
//!   carry → lower → release → retreat), with the search or the squaring in place of the lower;
//! - [`search`]: the force-guided search an integrator programs for a tight insertion;
//! - [`square`]: squaring a cube that hangs tilted in the grip against the table, before the
//!   search;
//! - [`oracle_switch`]: the switching search told each cycle's family: the place cell's
//!   ceiling, not a control;
//! - [`residual`]: what a residual policy corrects the search through;
//! - [`search_params`]: the search's tunable parameters and how values set them;
//! - `controls`: the task's rows of the table of controls ([`crate::controls::CONTROLS`]).

pub(crate) mod controls;
pub mod oracle_switch;
pub mod residual;
pub mod script;
pub mod search;
pub mod search_params;
pub mod square;

/// Old paths of the place script's items (`place::ScriptedPlace`, `place::PlacePhase`, …), kept
/// for one release.
pub use script::{
    CARRY_HEIGHT, CARRY_TOLERANCE, DROP_HEIGHT, LOWER_SPEED, PlacePhase, RELEASE_STEPS,
    RETREAT_HEIGHT, ScriptedPlace,
};
