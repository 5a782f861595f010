//! fairgrasp-planner: the scripted top-down grasp baseline for the FR3.
//!
//! - [`grasp`]: grasp, pre-grasp and lift poses from the observed cube; IK joint targets
//!   (closed-form branch nearest the current joints, QP IK as the fallback).
//! - [`motion`]: jerk-limited, time-synchronised joint trajectories (Ruckig).
//! - [`baseline`]: [`ScriptedGrasp`], a [`fairgrasp_env::episode::Policy`]: approach → descend →
//!   close → lift → hold, each phase with a timeout.
//! - [`phase`]: [`Phase`], where the script is (plan, approach, descend, close, lift, hold).
//! - [`place`]: [`ScriptedPlace`], the place task's open-loop script (the grasp, then carry,
//!   lower, release, retreat); [`place_search`]: the force-guided search that replaces the
//!   lower in the engineer's control; [`place_square`]: squaring a tilted cube on the table
//!   before it; [`place_residual`]: [`PlaceResidual`], what a residual
//!   policy corrects that search through.
//! - [`stack`]: the stack task's controls (the place script set down on a second cube) and its
//!   residual interface.
//! - [`oracle_switch`]: [`oracle_switch::OracleSwitch`], the switching search told each cycle's
//!   family: the place cell's ceiling, not a control.
//! - [`closed_loop`]: [`ClosedLoopGrasp`], the closed-loop script (re-plans, retries once) and
//!   the oracle (the same on the true cube pose).
//! - [`calibrated`]: [`CalibratedScript`], the open-loop script after a (simulated) camera
//!   calibration: the engineer's fix for a miscalibrated cell.
//! - [`correction`]: a task-space correction of the grasp and its map to joints (Jacobian).
//! - [`residual`]: [`ResidualScript`], what a residual policy corrects the script through, and
//!   [`OracleResidual`], the hand-written residual that uses the true pose through it.
//! - [`task_residual`]: [`TaskResidual`], what every task's residual interface is to the agent
//!   (the lift's [`ResidualScript`], the place's [`PlaceResidual`]); [`tasks`]: which one a
//!   preset's task uses.
//! - [`tuned_grip`]: [`TunedGripScript`], the open-loop script with the grip force an engineer
//!   tuned for the cell (the contact family's control).
//! - [`controls`]: every task's hand-written controls in one table ([`controls::CONTROLS`]):
//!   names, tunable parameters, how each is built.
//! - [`stream`]: an episode's joints as a real controller's servo stream (resampled with
//!   Ruckig, checked against the FR3's limits, JSON / CSV / `.npy`), and its playback in the env.

pub mod baseline;
pub mod calibrated;
pub mod closed_loop;
pub mod controls;
pub mod correction;
pub mod grasp;
pub mod motion;
pub mod oracle_switch;
pub mod phase;
pub mod place;
pub mod place_residual;
pub mod place_search;
pub mod place_square;
pub mod residual;
pub mod stack;
pub mod stream;
pub mod task_residual;
pub mod tasks;
pub mod tuned_grip;

pub use baseline::{BaselineConfig, CloseTiming, Phase, PlannedObject, ScriptedGrasp};
pub use calibrated::{CalibratedScript, CameraCalibration};
pub use closed_loop::{ClosedLoopConfig, ClosedLoopGrasp, CubeSource};
pub use correction::{CorrectionLimits, TaskCorrection};
pub use place::ScriptedPlace;
pub use place_residual::PlaceResidual;
pub use place_search::SearchParams;
pub use residual::{OracleResidual, ResidualScript};
pub use task_residual::TaskResidual;
pub use tuned_grip::TunedGripScript;
