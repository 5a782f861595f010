//! The rewards' weights, one table each, plain data: the distance reward's ([`DistanceReward`], `[task]`'s
//! `success_reward`, `collision_reward`, `distance_reward`) and the staged reward's
//! ([`StagedReward`], `[task.staged]`). The rewards themselves are computed in
//! `env/src/task/reward/`.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check, check_in};
use crate::config::error::ConfigError;

/// Weights of the distance reward (`task.reward = "distance"`): paid `success` on success,
/// `collision` on a collision or protective stop, else `distance` per metre still to go.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceReward {
    /// Reward on success (`task.success_reward`).
    pub success: f64,
    /// Reward on a collision or protective stop (`task.collision_reward`, negative).
    pub collision: f64,
    /// Dense reward per metre still to go \[1/m\] (`task.distance_reward`, negative).
    pub distance: f64,
    /// Paid every step, the last too (`task.time_reward`, negative or 0): what a cycle's time
    /// costs, for a cell on a takt. Default 0.
    pub time: f64,
}

impl Default for DistanceReward {
    fn default() -> Self {
        Self {
            success: 10.0,
            collision: -1.0,
            distance: -0.005,
            time: 0.0,
        }
    }
}

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

impl StagedReward {
    /// Refuses weights and scales outside their ranges, naming the field (`task.staged.*`).
    pub(crate) fn check(&self) -> Result<(), ConfigError> {
        // Weights beyond these make the per-step reward (and PPO's value targets) overflow long
        // before they mean anything: 1e308 trained to NaN and the error named the learning rate.
        let w = self;
        let weight = Bounds::closed(0.0, 1000.0);
        for (value, field, bounds, note) in [
            (w.reach, "task.staged.reach", weight, "(default 1)"),
            (w.grasp, "task.staged.grasp", weight, "(default 1)"),
            (w.lift, "task.staged.lift", weight, "(default 1)"),
            (
                w.reach_sharpness,
                "task.staged.reach_sharpness",
                weight.unit("1/m"),
                "(default 5)",
            ),
            (
                w.lift_sharpness,
                "task.staged.lift_sharpness",
                weight.unit("1/m"),
                "(default 50)",
            ),
        ] {
            check_in(value, field, bounds, note)?;
        }
        check(
            w.reach + w.grasp + w.lift > 0.0,
            "task.staged",
            w.reach + w.grasp + w.lift,
            "reach + grasp + lift must be positive (the per-step normaliser)",
        )?;
        for (value, field) in [
            (w.success, "task.staged.success"),
            (w.collision, "task.staged.collision"),
        ] {
            check_in(value, field, Bounds::closed(-1e4, 1e4), "")?;
        }
        Ok(())
    }
}
