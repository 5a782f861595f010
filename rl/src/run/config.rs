//! A training run's configuration (`config.toml` of a run folder): the recipe
//! ([`fairgrasp_eval::recipe::Recipe`], which evaluation and Python read too), as training
//! names it, and its limits.

pub use fairgrasp_eval::recipe::Recipe as TrainConfig;
pub use fairgrasp_eval::recipe::read::{MAX_ENVS, MAX_EVAL_EPISODES, MAX_THREADS, MAX_TIMESTEPS};
