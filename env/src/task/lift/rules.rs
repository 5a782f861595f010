//! The lift task's rules, pure functions of the state: lifted and held.

use crate::config::TaskConfig;
use crate::task::state::{TaskState, tcp_object_distance};

/// Lifted and held: the cube at least `task.lift_height` above its rest, both pads on it and
/// the TCP within 3 cm of its centre.
pub fn is_lifted(s: &TaskState, cfg: &TaskConfig) -> bool {
    let lifted = s.object[2] - s.object_rest_z >= cfg.lift_height;
    lifted && s.pad_contact[0] && s.pad_contact[1] && tcp_object_distance(s) < 0.03
}

/// How far the task still has to go \[m\]: the TCP to the cube's centre (what the
/// distance reward pays for in this task).
pub fn distance_to_go(s: &TaskState) -> f64 {
    tcp_object_distance(s)
}
