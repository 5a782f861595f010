//! The `Policy` trait shared by every controller (the scripted baseline, the PPO agent), and the
//! evaluation loop that runs any policy on a list of scenarios the same way; [`lockstep`] runs
//! several policies on one scenario, simulating once while their actions agree.

pub mod evaluate;
pub mod lockstep;
pub mod trajectory;

pub use evaluate::*;
pub use lockstep::run_lockstep;
