//! The grasping agents as PPO trains them. The agents themselves (config, policy input and
//! action, the residual's script) are burn-free and live in `fairgrasp-policy`
//! (`policy/src/agent/`), re-exported here; this room adds the env of every task as PPO sees it.
//!
//! - [`task_vec_env`]: the env of every task as a [`crate::ppo::vec_api::VecEnvironment`].

pub use fairgrasp_policy::agent::{grasp_agent, script};
pub mod task_vec_env;

pub use fairgrasp_policy::agent::{ACT_DIM, AgentConfig, GraspAgent, GripperMode, Mode};
pub use task_vec_env::TaskVecEnv;

/// The old name of [`TaskVecEnv`] (it runs every task, not only the grasp), kept for one release.
#[deprecated(
    note = "renamed `TaskVecEnv` (it runs every task); the old name goes in the next release"
)]
pub type GraspVecEnv = TaskVecEnv;
