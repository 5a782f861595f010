//! fairgrasp-rl: PPO in burn, the grasping env as PPO trains on it, and training runs.
//!
//! Three rooms, each building only on the ones before it:
//! - [`ppo`]: the algorithm (network, rollouts, GAE, losses, the update), nothing about grasping;
//! - [`agent`]: the grasp env as PPO sees it (the agents themselves are `fairgrasp-policy`'s,
//!   re-exported);
//! - [`run`]: training runs, checkpoints, resume, evaluation.
//!
//! What a trained policy needs after training (its checkpoint read and run without burn, the
//! shipped policies) is the `fairgrasp-policy` crate; the comparison is `fairgrasp-evaluate`.
//!
//! The `bench ppo` measurement lives in the `fairgrasp-bench` crate (`bench/`).

pub mod agent;
pub mod ppo;
pub mod run;
