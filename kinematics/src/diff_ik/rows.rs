//! What a task and a limit hand to the QP: weighted equality rows and inequality rows.

use crate::model::ArmModel;

/// One weighted row of a task: wants `jacobian · Δq = error`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaskRow {
    /// Row of the task Jacobian (per radian of each joint).
    pub jacobian: [f64; 6],
    /// Desired change of the task quantity this step (m or rad).
    pub error: f64,
    /// Weight (cost per unit² of residual).
    pub weight: f64,
}

/// One inequality row: `g · Δq ≤ h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LimitRow {
    /// Row of G.
    pub g: [f64; 6],
    /// Right-hand side \[rad\].
    pub h: f64,
}

/// Something the solver should achieve, as rows of error and Jacobian.
pub trait Task {
    /// Appends this task's rows at configuration `q` \[rad\].
    fn rows(&self, model: &ArmModel, q: &[f64; 6], out: &mut Vec<TaskRow>);
}

/// Something the step must respect, as inequality rows.
pub trait Limit {
    /// Appends this limit's rows at configuration `q` \[rad\].
    fn rows(&self, model: &ArmModel, q: &[f64; 6], out: &mut Vec<LimitRow>);
}
