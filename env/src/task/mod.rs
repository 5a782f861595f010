//! Success, failure and reward: pure functions of the state, testable without physics.

pub mod episode;
pub mod judge;
pub mod reward;
pub mod state;

pub use judge::*;
pub use state::*;
