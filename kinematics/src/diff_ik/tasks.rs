//! The tasks and limits of the differential IK: each gives only its rows (mink style).

use nalgebra::Vector3;

use crate::diff_ik::rows::{Limit, LimitRow, Task, TaskRow};
use crate::fk::EndFrame;
use crate::model::ArmModel;
use crate::pose::Pose;

/// Bring `frame` to `target` (in `base_link`).
///
/// Error: `[p* − p; log(R*·Rᵀ)]` (metres; rotation vector in radians, base frame); Jacobian: the
/// geometric Jacobian of `frame`. `position_cost` weighs metres, `orientation_cost` radians.
/// Errors longer than the clamps are shortened (Buss's clamped error), so that one step does not
/// trust the linear model over a large distance; `f64::INFINITY` disables a clamp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameTask {
    pub frame: EndFrame,
    pub target: Pose,
    pub position_cost: f64,
    pub orientation_cost: f64,
    /// Longest position error used in one step \[m\].
    pub position_clamp: f64,
    /// Longest orientation error used in one step \[rad\].
    pub orientation_clamp: f64,
}

impl FrameTask {
    /// A task without error clamps.
    pub fn new(frame: EndFrame, target: Pose, position_cost: f64, orientation_cost: f64) -> Self {
        Self {
            frame,
            target,
            position_cost,
            orientation_cost,
            position_clamp: f64::INFINITY,
            orientation_clamp: f64::INFINITY,
        }
    }
}

fn clamp_norm(v: Vector3<f64>, max: f64) -> Vector3<f64> {
    let n = v.norm();
    if n > max { v * (max / n) } else { v }
}

impl FrameTask {
    /// The position \[m\] and orientation \[rad\] errors at `q`.
    pub fn residual(&self, model: &ArmModel, q: &[f64; 6]) -> (f64, f64) {
        model.fk(q, self.frame).distance_to(&self.target)
    }
}

impl Task for FrameTask {
    fn rows(&self, model: &ArmModel, q: &[f64; 6], out: &mut Vec<TaskRow>) {
        let pose = model.fk(q, self.frame);
        let dp = clamp_norm(
            self.target.iso.translation.vector - pose.iso.translation.vector,
            self.position_clamp,
        );
        let dr = clamp_norm(
            (self.target.iso.rotation * pose.iso.rotation.inverse()).scaled_axis(),
            self.orientation_clamp,
        );
        let jac = model.jacobian(q, self.frame);
        for r in 0..6 {
            let (error, weight) = if r < 3 {
                (dp[r], self.position_cost)
            } else {
                (dr[r - 3], self.orientation_cost)
            };
            let row = jac.row(r);
            out.push(TaskRow {
                jacobian: [row[0], row[1], row[2], row[3], row[4], row[5]],
                error,
                weight,
            });
        }
    }
}

/// Pull the joints toward `target` \[rad\]: error `q* − q`, Jacobian I, cost per rad².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PostureTask {
    pub target: [f64; 6],
    pub cost: f64,
}

impl Task for PostureTask {
    fn rows(&self, _model: &ArmModel, q: &[f64; 6], out: &mut Vec<TaskRow>) {
        for i in 0..6 {
            let mut jacobian = [0.0; 6];
            jacobian[i] = 1.0;
            out.push(TaskRow {
                jacobian,
                error: self.target[i] - q[i],
                weight: self.cost,
            });
        }
    }
}

/// Keep `q + Δq` within the joint limits shrunk by `margin` \[rad\].
///
/// A joint already inside the margin may not go deeper but is not forced out, so the QP stays
/// feasible and, from any in-limit start, the limits themselves are never crossed.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct JointPositionLimit {
    pub margin: f64,
}

impl Limit for JointPositionLimit {
    fn rows(&self, model: &ArmModel, q: &[f64; 6], out: &mut Vec<LimitRow>) {
        for (i, spec) in model.joints.iter().enumerate() {
            let mut g = [0.0; 6];
            g[i] = 1.0;
            out.push(LimitRow {
                g,
                h: (spec.upper - self.margin - q[i]).max(0.0),
            });
            g[i] = -1.0;
            out.push(LimitRow {
                g,
                h: (q[i] - spec.lower - self.margin).max(0.0),
            });
        }
    }
}

/// `|Δq_i| ≤ v_max,i · dt`: the model's velocity limits over a step of `dt` seconds, scaled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VelocityLimit {
    /// Step duration \[s\].
    pub dt: f64,
    /// Fraction of the model's velocity limits to allow (1.0 = the full limits).
    pub scale: f64,
}

impl Limit for VelocityLimit {
    fn rows(&self, model: &ArmModel, _q: &[f64; 6], out: &mut Vec<LimitRow>) {
        for (i, spec) in model.joints.iter().enumerate() {
            let bound = spec.max_velocity * self.dt * self.scale;
            let mut g = [0.0; 6];
            g[i] = 1.0;
            out.push(LimitRow { g, h: bound });
            g[i] = -1.0;
            out.push(LimitRow { g, h: bound });
        }
    }
}
