//! fairgrasp-planner: every task's hand-written controls for the FR3, a folder per task, on
//! shared machinery.
//!
//! A folder per task (what its controls are, how a residual corrects them, its rows of the
//! table of controls):
//! - [`lift`]: grasp the cube and lift it. [`ScriptedGrasp`], a
//!   [`fairgrasp_env::episode::Policy`]: approach → descend → close → lift → hold, each phase
//!   with a timeout (the place and stack scripts start with it); [`ClosedLoopGrasp`], the
//!   closed-loop script (re-plans, retries once) and the oracle (the same on the true cube
//!   pose); [`CalibratedScript`], the open-loop script after a (simulated) camera calibration;
//!   [`TunedGripScript`], the open-loop script with the grip force an engineer tuned for the
//!   cell; [`ResidualScript`], what a residual policy corrects the script through, and
//!   [`OracleResidual`], the hand-written residual that uses the true pose through it.
//! - [`place`]: set the cube into a pocket. [`ScriptedPlace`], the open-loop script (the
//!   grasp, then carry, lower, release, retreat); [`place::search`]: the force-guided search
//!   that replaces the lower in the engineer's control; [`place::square`]: squaring a tilted
//!   cube on the table before it; [`PlaceResidual`], what a residual policy corrects that
//!   search through; [`place::oracle_switch`], the switching search told each cycle's family:
//!   the place cell's ceiling, not a control.
//! - [`stack`]: set the cube down on a second cube (the place script set down on its top) and
//!   its residual interface.
//!
//! Shared by every task:
//! - [`grasp`]: grasp, pre-grasp and lift poses from the observed cube; IK joint targets
//!   (closed-form branch nearest the current joints, QP IK as the fallback).
//! - [`motion`]: jerk-limited, time-synchronised joint trajectories (Ruckig).
//! - [`phase`]: [`Phase`], where the scripted grasp is (plan, approach, descend, close, lift,
//!   hold).
//! - [`correction`]: a task-space correction of the grasp and its map to joints (Jacobian).
//! - [`task_residual`]: [`TaskResidual`], what every task's residual interface is to the agent
//!   (the lift's [`ResidualScript`], the place's [`PlaceResidual`]); [`tasks`]: which one a
//!   preset's task uses.
//! - [`controls`]: every task's hand-written controls in one table ([`controls::CONTROLS`],
//!   assembled from each task's rows): names, tunable parameters, how each is built.
//! - [`stream`]: an episode's joints as a real controller's servo stream (resampled with
//!   Ruckig, checked against the FR3's limits, JSON / CSV / `.npy`), and its playback in the env.
//!
//! The modules' paths before the folders ([`baseline`], [`place_search`], [`residual`], …)
//! still name the same modules, for one release.

pub mod controls;
pub mod correction;
pub mod grasp;
pub mod lift;
pub mod motion;
pub mod phase;
pub mod place;
pub mod stack;
pub mod stream;
pub mod task_residual;
pub mod tasks;

/// Old path of [`lift::calibrated`], kept for one release.
pub use lift::calibrated;
/// Old path of [`lift::closed_loop`], kept for one release.
pub use lift::closed_loop;
/// Old path of [`lift::residual`], kept for one release.
pub use lift::residual;
/// Old path of [`lift::script`], kept for one release.
pub use lift::script as baseline;
/// Old path of [`lift::tuned_grip`], kept for one release.
pub use lift::tuned_grip;
/// Old path of [`place::oracle_switch`], kept for one release.
pub use place::oracle_switch;
/// Old path of [`place::residual`], kept for one release.
pub use place::residual as place_residual;
/// Old path of [`place::search`], kept for one release.
pub use place::search as place_search;
/// Old path of [`place::square`], kept for one release.
pub use place::square as place_square;

pub use correction::{CorrectionLimits, TaskCorrection};
pub use lift::calibrated::{CalibratedScript, CameraCalibration};
pub use lift::closed_loop::{ClosedLoopConfig, ClosedLoopGrasp, CubeSource};
pub use lift::residual::{OracleResidual, ResidualScript};
pub use lift::script::{BaselineConfig, CloseTiming, Phase, PlannedObject, ScriptedGrasp};
pub use lift::tuned_grip::TunedGripScript;
pub use place::residual::PlaceResidual;
pub use place::script::ScriptedPlace;
pub use place::search::SearchParams;
pub use task_residual::TaskResidual;
