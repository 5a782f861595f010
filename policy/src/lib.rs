//! fairgrasp-policy: the policies as they are used after training — read and run without burn,
//! so evaluating, comparing and exporting need none of the training stack.
//!
//! - [`agent`]: the grasping agents (config, policy input and action, the residual's script).
//! - [`recipe`]: the training recipe, one type for training, evaluation and Python, and the
//!   envs it gives.
//! - [`recipes`]: the training recipes shipped in `assets/experiments/`.
//! - [`burnpack`]: the weights of a checkpoint's `model.bpk`.
//! - [`actor`]: the policy network's actor as plain arrays (its mean action).
//! - [`checkpoint`]: a checkpoint's `meta.json` and verified weights, as a policy.
//! - [`shipped`]: the trained policies built into the binary.
//!
//! What is run with these policies (the comparison, the squeeze probe, the export to the
//! controller) is `fairgrasp-evaluate`.

pub mod actor;
pub mod agent;
pub mod burnpack;
pub mod checkpoint;
pub mod recipe;
pub mod recipes;
pub mod shipped;
