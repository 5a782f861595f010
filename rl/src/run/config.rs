//! A training run's configuration (`config.toml` of a run folder): the recipe
//! ([`fairgrasp_policy::recipe::Recipe`], which evaluation and Python read too), as training
//! names it, and its limits.

pub use fairgrasp_policy::recipe::Recipe as TrainConfig;
pub use fairgrasp_policy::recipe::read::{MAX_ENVS, MAX_EVAL_EPISODES, MAX_THREADS, MAX_TIMESTEPS};
