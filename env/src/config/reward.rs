//! The staged reward's weights and scales (`[task.staged]`), plain data; the reward itself is
//! computed in `env/src/task/reward.rs`.

use serde::{Deserialize, Serialize};

/// Weights and scales of the staged reward (`[task.staged]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StagedReward {
    /// Weight of the reach term.
    pub reach: f64,
    /// Reach sharpness \[1/m\] (ManiSkill 5, robosuite 10).
    pub reach_sharpness: f64,
    /// Weight of the grasp term (both pads on the cube).
    pub grasp: f64,
    /// Weight of the lift shaping, paid only while grasped.
    pub lift: f64,
    /// Lift sharpness \[1/m\]: the shaping reaches 1 at `task.lift_height`.
    pub lift_sharpness: f64,
    /// Paid on the step that succeeds (ends the episode).
    pub success: f64,
    /// Paid on a collision or a protective stop.
    pub collision: f64,
}

impl Default for StagedReward {
    fn default() -> Self {
        Self {
            reach: 1.0,
            reach_sharpness: 5.0,
            grasp: 1.0,
            lift: 1.0,
            lift_sharpness: 50.0,
            success: 20.0,
            collision: -1.0,
        }
    }
}
