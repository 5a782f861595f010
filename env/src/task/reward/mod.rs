//! The rewards a task pays, one file each with its weights in one table: the distance reward
//! ([`distance`], weights [`DistanceReward`]) and the staged reward ([`staged`], weights
//! [`StagedReward`]). [`reward`] pays the config's [`RewardKind`]. The evaluation's success
//! criterion does not depend on the reward.

pub mod distance;
pub mod staged;

pub use crate::config::reward::{DistanceReward, StagedReward};
use crate::config::{RewardKind, TaskConfig};
use crate::task::state::TaskState;
pub use distance::distance_reward;
pub use staged::staged_reward;

/// The reward of the config's [`RewardKind`] for a step that ended in state `s`.
pub fn reward(s: &TaskState, success: bool, collision: bool, cfg: &TaskConfig) -> f64 {
    match cfg.reward {
        RewardKind::Distance => distance_reward(s, success, collision, cfg),
        RewardKind::Staged => staged_reward(s, success, collision, cfg.lift_height, &cfg.staged),
    }
}
