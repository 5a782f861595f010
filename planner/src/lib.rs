//! fairgrasp-planner: the scripted top-down grasp baseline for the FR3.
//!
//! - [`grasp`]: grasp, pre-grasp and lift poses from the observed cube; IK joint targets
//!   (closed-form branch nearest the current joints, QP IK as the fallback).
//! - [`motion`]: jerk-limited, time-synchronised joint trajectories (Ruckig).
//! - [`baseline`]: [`ScriptedGrasp`], a [`fairgrasp_env::policy::Policy`]: approach → descend →
//!   close → lift → hold, each phase with a timeout.
//! - [`closed_loop`]: [`ClosedLoopGrasp`], the closed-loop script (re-plans, retries once) and
//!   the oracle (the same on the true cube pose).

pub mod baseline;
pub mod closed_loop;
pub mod grasp;
pub mod motion;

pub use baseline::{BaselineConfig, Phase, ScriptedGrasp};
pub use closed_loop::{ClosedLoopConfig, ClosedLoopGrasp, CubeSource};
