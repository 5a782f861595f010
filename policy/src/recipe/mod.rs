//! The training recipe (`assets/experiments/*.toml`, a run's `config.toml`): one type that
//! training (`fairgrasp-rl`), evaluation and Python read, so all of them meet the same env.
//!
//! - [`settings`]: the [`Recipe`] itself and its env configurations ([`Recipe::env_configs`],
//!   the one way from a recipe to its envs); [`read`]: a recipe file read and checked
//!   ([`Recipe::from_toml_file`], [`Recipe::validate`]).
//! - [`env`](mod@env): a preset's env as evaluations see it, and with the recipe's `[env]` table laid
//!   over it for training.
//! - [`overrides`]: a recipe with keyword overrides on its env-facing keys (Python's envs).
//! - [`ppo`]: the `[ppo]` table, PPO's hyper-parameters; [`kickstart`]: the `[kickstart]` table,
//!   a run's teachers.
//! - [`snapshot`]: the run folder's copy of a preset file, which a resumed run trains on.
//! - [`contradictions`]: settings that make each other mean nothing, refused naming both.

pub mod contradictions;
pub mod env;
pub mod kickstart;
pub mod overrides;
pub mod ppo;
pub mod read;
pub mod settings;
pub mod snapshot;

pub use env::{ENV_OVERRIDES, EnvFor, check_agent_env, overlay};
pub use read::RecipeError;
pub use settings::Recipe;
