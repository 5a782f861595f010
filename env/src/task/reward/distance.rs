//! The distance reward (`task.reward = "distance"`, the default; the seed recipe's reward,
//! rescaled): sparse on success and collision, dense on the distance the task still has to go.
//! Its weights are [`DistanceReward`] (`[task]`'s `success_reward`, `collision_reward`,
//! `distance_reward`).

use crate::config::TaskConfig;
pub use crate::config::reward::DistanceReward;
use crate::task::state::TaskState;
use crate::task::tasks::distance_to_go;

/// The distance reward of a step that ended in `s`, with `cfg`'s weights `w` (`cfg.distance`): `w.success` on success, `w.collision` on a
/// collision, else `w.distance ·` the distance still to go \[m\] ([`distance_to_go`]:
/// `|TCP − object|`, plus for the place task the cube's distance from its seat in the pocket);
/// plus `w.time` every step.
pub fn distance_reward(s: &TaskState, success: bool, collision: bool, cfg: &TaskConfig) -> f64 {
    let w = &cfg.distance;
    let r = if success {
        w.success
    } else if collision {
        w.collision
    } else {
        w.distance * distance_to_go(s, cfg)
    };
    // The time's cost, when it has one (adding 0 would turn a -0 into 0).
    if w.time == 0.0 { r } else { r + w.time }
}
