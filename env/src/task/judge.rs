//! The judgement of a step, whatever the task: success (the task's own rule), failure,
//! termination and the reward; pure functions of the state, testable without physics.

use serde::Serialize;

use crate::config::TaskConfig;
use crate::task::reward::reward;
use crate::task::state::TaskState;
pub use crate::task::tasks::is_success;

/// Why an episode ended without success.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Failure {
    /// Arm or gripper hit the table or itself: the two parts.
    Collision(String, String),
    /// The object fell off the table.
    ObjectOffTable,
    /// A robot part pushed on the cube or the table harder than `task.protective_stop_force`:
    /// the robot's part, the other part and the contact force \[N\].
    ProtectiveStop {
        robot_part: String,
        other_part: String,
        force_n: f64,
    },
}

impl Failure {
    /// A collision between two robot parts (arm or gripper against itself). A collision names
    /// the table first when the table is in it (`TaskEnv`'s one order of parts), and the cube
    /// is never in one.
    pub fn is_self_collision(&self) -> bool {
        matches!(self, Failure::Collision(first, _) if first != crate::sim::part::TABLE_PART_NAME)
    }
}

/// Has the object left the table (fallen below its top, or past its edge)?
pub fn is_off_table(s: &TaskState) -> bool {
    s.object[2] < s.table_height - 0.02
        || (0..2).any(|i| s.object_xy_from_table_centre[i].abs() > s.table_half_size[i])
}

/// What the task makes of one step.
#[derive(Clone, Debug, PartialEq)]
pub struct Judgement {
    /// The task succeeded ([`is_success`]: lifted and held, or placed).
    pub success: bool,
    /// Why the episode failed, if it did (never together with success).
    pub failure: Option<Failure>,
    /// The episode ends here (success, an ending collision, a protective stop, the object off
    /// the table).
    pub terminated: bool,
    pub reward: f64,
}

/// Judges a step: success, failure (a `collision` the contact scan found, or the object off
/// the table), whether the episode ends, and the reward.
pub fn judge(s: &TaskState, collision: Option<Failure>, cfg: &TaskConfig) -> Judgement {
    let success = is_success(s, cfg);
    let collided = collision.is_some();
    let collision_ends = collision.as_ref().is_some_and(|c| {
        cfg.terminate_on_collision || (cfg.terminate_on_self_collision && c.is_self_collision())
    });
    let failure = if success {
        None
    } else {
        collision.or_else(|| is_off_table(s).then_some(Failure::ObjectOffTable))
    };
    let terminated = success || collision_ends || failure == Some(Failure::ObjectOffTable);
    Judgement {
        success,
        failure,
        terminated,
        reward: reward(s, success, collided, cfg),
    }
}

/// `judgement` of a step with `task.collision_voids_success`: a success after a collision earlier
/// in the episode becomes that collision's failure, terminated and paid the collision's reward.
/// `first` holds the episode's first collision (this records it; the caller clears it at each
/// reset). A collision in the success step itself does not void it, as in an evaluation.
pub fn void_success_after_collision(
    judgement: Judgement,
    first: &mut Option<Failure>,
    s: &TaskState,
    cfg: &TaskConfig,
) -> Judgement {
    // A success step has no failure of its own, so `first` is still the earlier collision.
    if judgement.success
        && cfg.collision_voids_success
        && let Some(collision) = first
    {
        return Judgement {
            success: false,
            failure: Some(collision.clone()),
            terminated: true,
            reward: reward(s, false, true, cfg),
        };
    }
    if first.is_none() && matches!(judgement.failure, Some(Failure::Collision(..))) {
        *first = judgement.failure.clone();
    }
    judgement
}

/// Judges a step that a protective stop ended: never a success, always terminated (the robot
/// has stopped, whatever `terminate_on_collision`), and paid `collision_reward`. The failure is
/// the contact scan's `collision` if the stopped state has one (a part in the table or in the
/// arm: the diagnosis the env has always given), else `stop`: [`Failure::ProtectiveStop`] for
/// the cube, [`Failure::Collision`] for the table (any robot–table touch is a collision).
pub fn judge_protective_stop(
    s: &TaskState,
    collision: Option<Failure>,
    stop: Failure,
    cfg: &TaskConfig,
) -> Judgement {
    Judgement {
        success: false,
        failure: Some(collision.unwrap_or(stop)),
        terminated: true,
        reward: reward(s, false, true, cfg),
    }
}
