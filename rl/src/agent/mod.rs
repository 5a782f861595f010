//! The grasping agents: what a network's output means on the FR3 grasp env. Residual agents
//! correct the scripted baseline; pure agents act alone. Builds on [`crate::ppo`] (the vector-env
//! interface) and on env and planner; the runs ([`crate::run`]) build on it.
//!
//! - [`grasp_agent`]: the agent's config and its policy (network + script), `ACT_DIM`.
//! - [`script`]: the scripted part a residual agent corrects.
//! - [`grasp_env`]: the grasp env as PPO sees it (a [`crate::ppo::vec_api::VecEnvironment`]).

pub mod grasp_agent;
pub mod grasp_env;
pub mod script;

pub use grasp_agent::{ACT_DIM, AgentConfig, GraspAgent, GripperMode, Mode};
pub use grasp_env::GraspVecEnv;
