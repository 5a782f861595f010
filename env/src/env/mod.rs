//! `TaskEnv`: the gym-style interface. `reset(seed)` and `step(&Action)`.
//!
//! An action is 6 joint-velocity commands and 1 gripper command, each in [-1, 1]: joints move at
//! `action · arm.action_scale` rad/s (or, with `arm.action_space = "tcp"`, entries 0–3 are the
//! TCP's velocity and yaw rate, see [`crate::robot::tcp_action`]); the gripper closes toward travel
//! `(g + 1)/2 · 42.5 mm` (−1 open, +1 closed) with a limited force. `terminated` means success or failure, `truncated`
//! the time limit or a physics fault; never both.

pub mod diagnostics;
mod drive;
pub mod free_space;
pub mod obs;
pub mod spaces;
pub mod step;
pub mod task_env;
mod task_facts;

pub use task_env::*;
