//! [`TaskResidual`]: what every task's residual interface is to the agent that drives it — the
//! lift task's [`ResidualScript`](crate::ResidualScript), the place task's
//! [`PlaceResidual`](crate::PlaceResidual), and the next task's.
//!
//! A task-space residual policy (`agent.action_space = "tcp"` in residual mode) reads the
//! observation and [`FEATURE_DIM`] values the interface adds, and writes 7 values in [-1, 1]
//! that the interface turns into the env's action. An all-zero output is the task's engineered
//! control exactly. Which interface a preset's task uses is registered in [`crate::tasks`].

use fairgrasp_env::episode::Outcome;
use fairgrasp_env::{Action, Observation};

/// Values every task's interface adds to the policy input: one size whatever the task, so that a
/// task-space residual's input has one shape.
pub const FEATURE_DIM: usize = 19;

/// Values of a residual policy's output.
pub const OUTPUT_DIM: usize = 7;

/// A task's residual interface: the engineered control a residual policy corrects, and how it
/// reads the policy's output and what it shows the policy.
pub trait TaskResidual: Send {
    /// Starts the episode of scenario `seed`.
    fn reset(&mut self, seed: u64);

    /// The env action for the policy's `action` (each in [-1, 1]) at `obs`.
    fn act(&mut self, obs: &Observation, action: &[f64; OUTPUT_DIM]) -> Action;

    /// Writes the [`TaskResidual::feature_names`] values for the next decision at `obs`.
    fn write_features(&self, obs: &Observation, out: &mut [f64; FEATURE_DIM]);

    /// The names of the added values, in order.
    fn feature_names(&self) -> &'static [&'static str; FEATURE_DIM];

    /// The bounds of each added value, in order, given `object_bound`: a bound on every
    /// coordinate of the observed cube's position in `base_link` \[m\].
    fn feature_bounds(&self, object_bound: f64) -> [(f64, f64); FEATURE_DIM];

    /// What each of the policy's output values commands, in order.
    fn output_names(&self) -> [&'static str; OUTPUT_DIM];

    /// The script's phase name (for recorded trajectories).
    fn phase(&self) -> &'static str;

    /// Set when the script has given up (no IK solution).
    fn gave_up(&self) -> Option<Outcome>;

    /// The grip force per finger \[N\] the policy's squeeze asks for; `None` for an interface
    /// without a squeeze (the env's `gripper.force` then holds).
    fn grip_force(&self) -> Option<f64> {
        None
    }
}
