//! fairgrasp-rl: PPO in burn, the grasping agents, training runs and the comparison.
//!
//! Four rooms, each building only on the ones before it:
//! - [`ppo`]: the algorithm (network, rollouts, GAE, losses, the update), nothing about grasping;
//! - [`agent`]: residual and pure grasping agents, and the grasp env as PPO sees it;
//! - [`run`]: training runs, checkpoints, resume, evaluation, the shipped policies;
//! - [`compare`]: every method on the same scenario sets (the `compare` experiment).
//!
//! The `bench ppo` measurement lives in the `fairgrasp-bench` crate (`bench/`).

pub mod agent;
pub mod compare;
pub mod ppo;
pub mod run;
