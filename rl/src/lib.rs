//! fairgrasp-rl: PPO in burn, the grasping agents, training runs and the comparison.
//!
//! Three rooms, each building only on the ones before it:
//! - [`ppo`]: the algorithm (network, rollouts, GAE, losses, the update), nothing about grasping;
//! - [`agent`]: residual and pure grasping agents, and the grasp env as PPO sees it;
//! - [`run`]: training runs, checkpoints, resume, evaluation.
//!
//! What a trained policy needs after training (its checkpoint read and run without burn, the
//! shipped policies, the comparison) is the `fairgrasp-eval` crate.
//!
//! The `bench ppo` measurement lives in the `fairgrasp-bench` crate (`bench/`).

pub mod agent;
pub mod ppo;
pub mod run;
