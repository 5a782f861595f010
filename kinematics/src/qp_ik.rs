//! Iterative IK by repeated QP steps ([`crate::diff_ik`]), with seeded random restarts.
//!
//! Each iteration solves the frame task under the joint-position and step limits with
//! Levenberg–Marquardt damping `λ = λ₀ + κ·‖e‖²` (large far from the target, vanishing at it) and
//! takes the full step. An attempt that stalls or runs out of iterations restarts from a random
//! in-limit configuration drawn from `seed`, as TRAC-IK does; the same seed gives the same answer.
//!
//! The restart loop (the crate's `restart` module) is shared with [`crate::chain_ik`]; the step
//! is this solver's own: [`crate::diff_ik`]'s QP on the FR3's model, its step limit scaled by
//! each joint's velocity limit, `limit_margin` kept from the limits, and a choice of frame
//! (flange or TCP). Solving the FR3 as a URDF chain would step otherwise (a uniform step limit,
//! the active set's answers instead of clarabel's, last bits apart) and move every grasp the
//! planner computes with this solver.

use crate::diff_ik::{
    FrameTask, JointPositionLimit, QpError, QpWorkspace, VelocityLimit, solve_step,
};
use crate::fk::EndFrame;
use crate::model::ArmModel;
use crate::pose::Pose;
pub use crate::restart::IterativeIkSolution;
use crate::restart::{
    RestartSettings, Restarted, RestartedIk, SplitMix64, finite_target_and_start,
    solve_with_restarts,
};

/// Settings of [`ArmModel::ik_qp`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QpIkOptions {
    /// Which frame to place at the target.
    pub frame: EndFrame,
    /// Converged when the position error is at most this \[m\].
    pub position_tolerance: f64,
    /// … and the orientation error at most this \[rad\].
    pub orientation_tolerance: f64,
    /// Iterations per attempt.
    pub max_iterations: usize,
    /// Attempts: the first from the given start, the rest from random in-limit configurations.
    pub max_attempts: usize,
    /// Largest step of any joint per iteration \[rad\] (the velocity limit over one iteration).
    pub max_step: f64,
    /// Distance kept from the joint limits \[rad\].
    pub limit_margin: f64,
    /// Constant damping λ₀ \[per rad²\].
    pub damping: f64,
    /// Error-dependent damping κ: λ = λ₀ + κ·‖e‖² (e in m and rad).
    pub error_damping: f64,
    /// Weight of position error \[per m²\].
    pub position_cost: f64,
    /// Weight of orientation error \[per rad²\].
    pub orientation_cost: f64,
    /// Longest position error trusted in one step \[m\].
    pub position_clamp: f64,
    /// Longest orientation error trusted in one step \[rad\].
    pub orientation_clamp: f64,
    /// Seed of the restarts' random configurations.
    pub seed: u64,
}

impl Default for QpIkOptions {
    fn default() -> Self {
        Self {
            frame: EndFrame::Flange,
            position_tolerance: 1e-4,
            orientation_tolerance: 1e-3,
            max_iterations: 40,
            max_attempts: 60,
            max_step: 0.5,
            limit_margin: 0.0,
            damping: 1e-9,
            error_damping: 1e-3,
            position_cost: 1.0,
            orientation_cost: 0.25,
            position_clamp: 0.2,
            orientation_clamp: 0.5,
            seed: 0,
        }
    }
}

/// A converged solve.
pub type QpIkSolution = IterativeIkSolution<[f64; 6]>;

/// Why the QP IK did not reach the target.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QpIkError {
    /// The start configuration is outside the joint limits.
    #[error("start joint j{} = {value:.4} rad is outside its limits [{lower:.4}, {upper:.4}]", joint + 1)]
    StartOutOfLimits {
        joint: usize,
        value: f64,
        lower: f64,
        upper: f64,
    },
    /// The target or the start is not finite.
    #[error("the target pose or the start joints are not finite")]
    NonFinite,
    /// Out of iterations and attempts; the best configuration found is reported.
    #[error(
        "did not converge: best residual {position_error_m:.3e} m / {orientation_error_rad:.3e} rad after {iterations} QP steps in {attempts} attempts"
    )]
    NotConverged {
        best_joints: [f64; 6],
        position_error_m: f64,
        orientation_error_rad: f64,
        iterations: usize,
        attempts: usize,
    },
    /// A QP step failed.
    #[error(transparent)]
    Qp(#[from] QpError),
}

impl ArmModel {
    /// Places `options.frame` at `target` (in `base_link`) starting from `start`, by QP steps.
    pub fn ik_qp(
        &self,
        target: &Pose,
        start: &[f64; 6],
        options: &QpIkOptions,
    ) -> Result<QpIkSolution, QpIkError> {
        let mut ws = QpWorkspace::default();
        self.ik_qp_with(target, start, options, &mut ws)
    }

    /// [`ArmModel::ik_qp`] reusing a workspace (saves the solver setup between calls).
    pub fn ik_qp_with(
        &self,
        target: &Pose,
        start: &[f64; 6],
        options: &QpIkOptions,
        ws: &mut QpWorkspace,
    ) -> Result<QpIkSolution, QpIkError> {
        self.check_qp_start(target, start)?;
        let mut problem = FrameProblem::new(self, target, options, ws);
        let settings = RestartSettings::new(
            (options.position_tolerance, options.orientation_tolerance),
            options.max_iterations,
            options.max_attempts,
            options.seed,
        );
        match solve_with_restarts(&mut problem, start, &settings)? {
            Restarted::Converged(solution) => Ok(solution),
            Restarted::NotConverged(r) => Err(QpIkError::NotConverged {
                best_joints: r.joints,
                position_error_m: r.position_error_m,
                orientation_error_rad: r.orientation_error_rad,
                iterations: r.iterations,
                attempts: r.attempts,
            }),
        }
    }

    /// Refuses a non-finite target or start, and a start outside the joint limits.
    fn check_qp_start(&self, target: &Pose, start: &[f64; 6]) -> Result<(), QpIkError> {
        if !finite_target_and_start(target, start) {
            return Err(QpIkError::NonFinite);
        }
        match self.first_limit_violation(start) {
            Some((joint, value)) => Err(QpIkError::StartOutOfLimits {
                joint,
                value,
                lower: self.joints[joint].lower,
                upper: self.joints[joint].upper,
            }),
            None => Ok(()),
        }
    }
}

/// The FR3's frame task as a [`RestartedIk`] problem: its residual, and one QP step of
/// [`crate::diff_ik`] under the position and step limits.
struct FrameProblem<'a> {
    model: &'a ArmModel,
    options: &'a QpIkOptions,
    task: FrameTask,
    position_limit: JointPositionLimit,
    /// The largest step per iteration as a velocity limit: `max_step` for the slowest joint, the
    /// others in proportion to their velocity limits.
    step_limit: VelocityLimit,
    ws: &'a mut QpWorkspace,
}

impl<'a> FrameProblem<'a> {
    fn new(
        model: &'a ArmModel,
        target: &Pose,
        options: &'a QpIkOptions,
        ws: &'a mut QpWorkspace,
    ) -> Self {
        let task = FrameTask {
            position_clamp: options.position_clamp,
            orientation_clamp: options.orientation_clamp,
            ..FrameTask::new(
                options.frame,
                *target,
                options.position_cost,
                options.orientation_cost,
            )
        };
        let min_velocity = model
            .velocity_limits()
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        Self {
            model,
            options,
            task,
            position_limit: JointPositionLimit {
                margin: options.limit_margin,
            },
            step_limit: VelocityLimit {
                dt: options.max_step / min_velocity,
                scale: 1.0,
            },
            ws,
        }
    }
}

impl RestartedIk for FrameProblem<'_> {
    type Joints = [f64; 6];
    /// The QP linearises at the configuration itself.
    type Linearisation = ();
    type Error = QpIkError;

    fn evaluate(&mut self, q: &[f64; 6]) -> (f64, f64, ()) {
        let (dp, dr) = self.task.residual(self.model, q);
        (dp, dr, ())
    }

    fn step(&mut self, q: &mut [f64; 6], (dp, dr): (f64, f64), _: ()) -> Result<(), QpIkError> {
        let o = self.options;
        let damping = o.damping
            + o.error_damping * (o.position_cost * dp * dp + o.orientation_cost * dr * dr);
        let dq = solve_step(
            self.model,
            q,
            &[&self.task],
            &[&self.position_limit, &self.step_limit],
            damping,
            self.ws,
        )?;
        for (i, joint) in self.model.joints.iter().enumerate() {
            // The QP's interior-point answer may sit 1e-12 outside a bound.
            q[i] = (q[i] + dq[i]).clamp(joint.lower, joint.upper);
        }
        Ok(())
    }

    /// Within the limits less `limit_margin`.
    fn draw(&self, rng: &mut SplitMix64) -> [f64; 6] {
        let margin = self.options.limit_margin;
        self.model.joints.map(|j| {
            let (lo, hi) = (j.lower + margin, j.upper - margin);
            lo + (hi - lo) * rng.next_unit()
        })
    }
}
