//! The seed recipe's reward (`task.reward = "seed"`, the default), rescaled: sparse on success
//! and collision, dense on the distance the task still has to go. Its weights are
//! [`SeedReward`] (`[task]`'s `success_reward`, `collision_reward`, `distance_reward`).

pub use crate::config::reward::SeedReward;
use crate::task::state::TaskState;
use crate::task::{lift, place};

/// The seed reward of a step that ended in `s`: `w.success` on success, `w.collision` on a
/// collision, else `w.distance ·` the distance still to go \[m\]: `|TCP − object|` (lift,
/// [`lift::distance_to_go`]), plus the cube's distance from its seat in the pocket (place,
/// [`place::distance_to_go`]).
pub fn seed_reward(s: &TaskState, success: bool, collision: bool, w: &SeedReward) -> f64 {
    if success {
        w.success
    } else if collision {
        w.collision
    } else {
        let to_go = match &s.place {
            Some(f) => place::distance_to_go(s, f),
            None => lift::distance_to_go(s),
        };
        w.distance * to_go
    }
}
