//! fairgrasp-eval: trained policies as they are used after training — read and run without
//! burn, so evaluating, comparing and exporting need none of the training stack.
//!
//! - [`agent`]: the grasping agents (config, policy input and action, the residual's script).
//! - [`recipe`]: the env a training recipe trains on.
//! - [`recipes`]: the training recipes shipped in `assets/experiments/`.
//! - [`burnpack`]: the weights of a checkpoint's `model.bpk`.
//! - [`actor`]: the policy network's actor as plain arrays (its mean action).

pub mod actor;
pub mod agent;
pub mod burnpack;
pub mod recipe;
pub mod recipes;
