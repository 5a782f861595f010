//! Where the tasks are registered: one arm per task in each rule every task must have (its
//! success, how far it still has to go), chosen by the facts the state carries (the place task's
//! [`PlaceFacts`](crate::task::state::PlaceFacts), else the lift task). A task's rules are in its
//! own folder ([`crate::task::lift`], [`crate::task::place`]).

use crate::config::TaskConfig;
use crate::task::state::TaskState;
use crate::task::{lift, place};

/// The task's success: for the lift task lifted and held ([`lift::is_lifted`]), for the place
/// task seated, released and clear ([`place::is_placed`]).
pub fn is_success(s: &TaskState, cfg: &TaskConfig) -> bool {
    match &s.place {
        Some(f) => place::is_placed(s, f, &cfg.place),
        None => lift::is_lifted(s, cfg),
    }
}

/// How far the task still has to go \[m\] (what the distance reward pays for): the
/// TCP to the cube (lift, [`lift::distance_to_go`]), plus the cube to its seat in the pocket
/// (place, [`place::distance_to_go`]).
pub fn distance_to_go(s: &TaskState) -> f64 {
    match &s.place {
        Some(f) => place::distance_to_go(s, f),
        None => lift::distance_to_go(s),
    }
}
