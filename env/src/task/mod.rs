//! Success, failure and reward: pure functions of the state, testable without physics. The
//! lift task's rules are in [`mod@judge`] and [`mod@reward`], the place task's in [`place`].

pub mod episode;
pub mod judge;
pub mod place;
pub mod reward;
pub mod state;

pub use judge::*;
pub use state::*;
