//! Success, failure and reward: pure functions of the state, testable without physics.
//!
//! A task is a folder: [`lift`] (the default), [`place`] and [`stack`], each with its rules (its success,
//! how far it still has to go), registered in [`tasks`] (one arm per task in each rule). What
//! every task shares is named by concern: the state a step is judged on ([`state`]), the
//! judgement of a step ([`mod@judge`]: success by the task's rule, failure, termination), the
//! rewards ([`mod@reward`]: the seed and the staged reward, each with its weights in one table)
//! and the episode's record ([`episode`]).

pub mod episode;
pub mod judge;
pub mod lift;
pub mod place;
pub mod reward;
pub mod stack;
pub mod state;
pub mod tasks;

pub use judge::*;
pub use reward::{distance_reward, reward};
pub use state::*;
