//! Where the tasks' rules are registered: one arm per task in each rule every task must have
//! (its success, how far it still has to go). A task's rules are in its own folder
//! ([`crate::task::lift`], [`crate::task::place`], [`crate::task::stack`]); a task with a
//! fixture is judged on the fixture's facts ([`PlaceFacts`](crate::task::state::PlaceFacts)),
//! which the state carries whenever the scene has one.

use crate::config::{TaskConfig, TaskKind};
use crate::task::state::TaskState;
use crate::task::{lift, place, stack};

/// The task's success: for the lift task lifted and held ([`lift::is_lifted`]), for the place
/// task seated, released and clear ([`place::is_placed`]), for the stack task stacked, released
/// and clear ([`stack::is_success`]).
pub fn is_success(s: &TaskState, cfg: &TaskConfig) -> bool {
    match (cfg.kind, &s.place) {
        (TaskKind::Lift, _) => lift::is_lifted(s, cfg),
        (TaskKind::Place, Some(f)) => place::is_placed(s, f, &cfg.place),
        (TaskKind::Stack, Some(f)) => stack::is_success(s, f, &cfg.stack),
        (TaskKind::Place | TaskKind::Stack, None) => false,
    }
}

/// How far the task still has to go \[m\] (what the distance reward pays for): the TCP to the
/// cube (lift, [`lift::distance_to_go`]), plus the cube to its seat in the pocket (place,
/// [`place::distance_to_go`]) or on the second cube (stack, [`stack::distance_to_go`]).
pub fn distance_to_go(s: &TaskState, cfg: &TaskConfig) -> f64 {
    match (cfg.kind, &s.place) {
        (TaskKind::Place, Some(f)) => place::distance_to_go(s, f),
        (TaskKind::Stack, Some(f)) => stack::distance_to_go(s, f),
        _ => lift::distance_to_go(s),
    }
}
