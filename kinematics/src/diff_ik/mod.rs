//! Differential IK as one QP, mink/pink style: tasks give an error and a Jacobian, limits give
//! inequality rows, and [`solve_step`] stacks them and calls clarabel.
//!
//! The unknown is the joint displacement `Δq` \[rad\] of one step. A task with rows
//! `(j_k, e_k, w_k)` wants `j_k · Δq = e_k`; a limit row `(g, h)` demands `g · Δq ≤ h`.
//! The QP is
//!
//! ```text
//! minimise   ½ Σ_k w_k (j_k·Δq − e_k)² + ½ λ ‖Δq‖²     subject to   G Δq ≤ h
//! ```
//!
//! with λ > 0 the damping that keeps it strictly convex at singularities.
//!
//! What lives here: the rows and the two traits (`rows.rs`), the tasks and limits
//! (`tasks.rs`), and the stacked QP step with its reusable clarabel workspace (`step.rs`). It builds
//! on the kinematics below it (model, FK); the iterative solvers above it
//! ([`crate::qp_ik`]) and other crates import it through the names re-exported here.

mod rows;
mod step;
mod tasks;

pub use rows::{Limit, LimitRow, Task, TaskRow};
pub use step::{QpError, QpWorkspace, solve_step};
pub use tasks::{FrameTask, JointPositionLimit, PostureTask, VelocityLimit};
