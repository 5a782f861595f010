//! The grasping agents: what a network's output means on the FR3 grasp env. Residual agents
//! correct the scripted baseline; pure agents act alone (through the env's task-space action).
//! No network here: a [`grasp_agent::GraspAgent`] takes its mean action from a function.
//!
//! - [`grasp_agent`]: the agent's config, its policy input and action, `ACT_DIM`.
//! - [`script`]: the scripted part a residual agent corrects.
//! - [`env_agent`]: one env's side of an agent (its script and the baseline's action), as the
//!   trainer and Python step it.

pub mod env_agent;
pub mod grasp_agent;
pub mod script;

pub use env_agent::EnvAgent;
pub use grasp_agent::{ACT_DIM, AgentConfig, GraspAgent, GripperMode, Mode};
