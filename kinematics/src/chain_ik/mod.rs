//! Inverse kinematics for any serial arm read from a URDF (N movable joints): damped QP steps
//! within the joint limits, with seeded random restarts, as TRAC-IK restarts its solvers.
//!
//! Each iteration solves `min ½·dqᵀ(JᵀWJ + λI)dq − (JᵀWe)ᵀdq` subject to the joint limits and a
//! largest step per joint: `e` is the tip's error `[p* − p; log(R*·Rᵀ)]` (m, rad, root frame)
//! clamped to a trusted length, `W` weighs position against orientation, and the
//! Levenberg–Marquardt damping `λ = λ₀ + κ·‖e‖²` vanishes at the target. When the unconstrained
//! minimiser (one N×N Cholesky solve) is within the bounds it is the QP's optimum; otherwise
//! clarabel solves the bounded QP. The FR3's own IK stays the closed form
//! ([`crate::analytic_ik`]); this serves every other chain (a 7-joint arm, the FR5, a tip other
//! than the last link).

mod jacobian;
mod solve;
mod step;

pub use solve::{ChainIk, ChainIkError, ChainIkOptions, ChainIkSolution};
