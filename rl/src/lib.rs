//! fairgrasp-rl: PPO in burn, and the residual grasping agent.
//!
//! - [`gae`]: generalised advantage estimation, advantage normalisation, explained variance.
//! - [`model`]: the actor-critic MLPs; [`init`]: their weights from the run's own generator.
//! - [`normalizer`]: running observation statistics.
//! - [`ppo`]: the PPO loop, CleanRL style; [`ppo_loss`]: its losses and ratio diagnostics.
//! - [`gaussian`]: the policy's distribution, its one log-probability.
//! - [`rollout`]: the rollout buffer, one flat buffer per quantity.
//! - [`vec_api`]: what PPO needs from environments; [`point_mass`]: a small task PPO must solve.
//! - [`grasp_env`]: the grasp env as PPO sees it; [`agent`]: residual or pure agent;
//!   [`action_map`]: its task-space action.
//! - [`train_config`], [`train`], [`checkpoint`], [`evaluate`]: training runs and their files.
//! - [`bench`]: the `bench ppo` measurement.

pub mod action_map;
pub mod agent;
pub mod bench;
pub mod checkpoint;
pub mod compare;
pub mod evaluate;
pub mod gae;
pub mod gaussian;
pub mod grasp_env;
pub mod init;
pub mod model;
pub mod normalizer;
pub mod point_mass;
pub mod ppo;
pub mod ppo_config;
pub mod ppo_error;
pub mod ppo_loss;
pub mod resume;
pub mod rollout;
pub mod script;
pub mod shipped;
pub mod train;
pub mod train_config;
pub mod vec_api;
