//! The grasping agents as PPO trains them. The agents themselves (config, policy input and
//! action, the residual's script) are burn-free and live in `fairgrasp-policy`
//! (`policy/src/agent/`), re-exported here; this room adds the grasp env as PPO sees it.
//!
//! - [`grasp_env`]: the grasp env as a [`crate::ppo::vec_api::VecEnvironment`].

pub use fairgrasp_policy::agent::{grasp_agent, script};
pub mod grasp_env;

pub use fairgrasp_policy::agent::{ACT_DIM, AgentConfig, GraspAgent, GripperMode, Mode};
pub use grasp_env::GraspVecEnv;
