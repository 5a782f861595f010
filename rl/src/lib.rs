//! fairgrasp-rl: PPO in burn, and the residual grasping agent.
//!
//! - [`gae`]: generalised advantage estimation, advantage normalisation, explained variance.
//! - [`model`]: the actor-critic MLPs.
//! - [`normalizer`]: running observation statistics.
//! - [`ppo`]: the PPO loop, CleanRL style.
//! - [`vec_api`]: what PPO needs from environments; [`point_mass`]: a small task PPO must solve.

pub mod agent;
pub mod checkpoint;
pub mod compare;
pub mod evaluate;
pub mod gae;
pub mod grasp_env;
pub mod model;
pub mod normalizer;
pub mod point_mass;
pub mod ppo;
pub mod ppo_config;
pub mod shipped;
pub mod train;
pub mod vec_api;
