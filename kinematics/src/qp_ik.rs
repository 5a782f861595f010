//! Iterative IK by repeated QP steps ([`crate::diff_ik`]), with seeded random restarts.
//!
//! Each iteration solves the frame task under the joint-position and step limits with
//! Levenberg–Marquardt damping `λ = λ₀ + κ·‖e‖²` (large far from the target, vanishing at it) and
//! takes the full step. An attempt that stalls or runs out of iterations restarts from a random
//! in-limit configuration drawn from `seed`, as TRAC-IK does; the same seed gives the same answer.

use serde::Serialize;

use crate::diff_ik::{
    FrameTask, JointPositionLimit, QpError, QpWorkspace, VelocityLimit, solve_step,
};
use crate::fk::EndFrame;
use crate::model::ArmModel;
use crate::pose::Pose;
use crate::restart::SplitMix64;

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

/// A converged QP IK solve.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct QpIkSolution {
    /// Joint angles \[rad\], within the limits.
    pub joints: [f64; 6],
    /// Position error at the end \[m\].
    pub position_error_m: f64,
    /// Orientation error at the end \[rad\].
    pub orientation_error_rad: f64,
    /// QP steps taken over all attempts.
    pub iterations: usize,
    /// Attempts used (1 = converged from the given start).
    pub attempts: usize,
}

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
        let finite_target = target
            .xyz()
            .iter()
            .chain(&target.quat_xyzw())
            .all(|v| v.is_finite());
        if !finite_target || !start.iter().all(|v| v.is_finite()) {
            return Err(QpIkError::NonFinite);
        }
        if let Some((joint, value)) = self.first_limit_violation(start) {
            let spec = self.joints[joint];
            return Err(QpIkError::StartOutOfLimits {
                joint,
                value,
                lower: spec.lower,
                upper: spec.upper,
            });
        }
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
        let position_limit = JointPositionLimit {
            margin: options.limit_margin,
        };
        let min_velocity = self
            .velocity_limits()
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let step_limit = VelocityLimit {
            dt: options.max_step / min_velocity,
            scale: 1.0,
        };
        let mut rng = SplitMix64(options.seed);
        let mut best = (f64::INFINITY, *start, 0.0, 0.0);
        let mut iterations = 0;
        let mut q = *start;
        for attempt in 1..=options.max_attempts {
            if attempt > 1 {
                q = self.joints.map(|j| {
                    let (lo, hi) = (
                        j.lower + options.limit_margin,
                        j.upper - options.limit_margin,
                    );
                    lo + (hi - lo) * rng.next_unit()
                });
            }
            let mut stalled_since = (f64::INFINITY, 0);
            for it in 0..=options.max_iterations {
                let (dp, dr) = task.residual(self, &q);
                let score = dp / options.position_tolerance + dr / options.orientation_tolerance;
                if score < best.0 {
                    best = (score, q, dp, dr);
                }
                if dp <= options.position_tolerance && dr <= options.orientation_tolerance {
                    return Ok(QpIkSolution {
                        joints: q,
                        position_error_m: dp,
                        orientation_error_rad: dr,
                        iterations,
                        attempts: attempt,
                    });
                }
                // A stall: less than 10 % progress over 8 steps.
                if score < 0.9 * stalled_since.0 {
                    stalled_since = (score, it);
                } else if it - stalled_since.1 >= 8 || it == options.max_iterations {
                    break;
                }
                let damping = options.damping
                    + options.error_damping
                        * (options.position_cost * dp * dp + options.orientation_cost * dr * dr);
                let dq = solve_step(
                    self,
                    &q,
                    &[&task],
                    &[&position_limit, &step_limit],
                    damping,
                    ws,
                )?;
                iterations += 1;
                for i in 0..6 {
                    // The QP's interior-point answer may sit 1e-12 outside a bound.
                    q[i] = (q[i] + dq[i]).clamp(self.joints[i].lower, self.joints[i].upper);
                }
            }
        }
        Err(QpIkError::NotConverged {
            best_joints: best.1,
            position_error_m: best.2,
            orientation_error_rad: best.3,
            iterations,
            attempts: options.max_attempts,
        })
    }
}
