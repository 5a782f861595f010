//! The `Policy` trait shared by every controller (the scripted baseline, the PPO agent), and the
//! evaluation loop that runs any policy on a list of scenarios the same way.

pub mod evaluate;
pub mod trajectory;

pub use evaluate::*;
