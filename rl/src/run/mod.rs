//! Training runs and their files: the config, the run folder (`config.toml`, `metrics.csv`,
//! `checkpoints/`, `eval.json`), checkpoints and resume, evaluation of a trained network, and
//! the shipped policies. Builds on [`crate::ppo`] and [`crate::agent`].
//!
//! - [`config`] and [`error`]: what a run needs, and why it could not start or go on.
//! - [`train`]: the training loop over a run folder; [`metrics`]: its `metrics.csv` rows;
//!   [`tensorboard`]: the same values as TensorBoard event files.
//! - [`checkpoint`]: saving and loading a network with its metadata, atomically and checked.
//! - [`folder`]: what a run folder holds and who may train in it; [`resume`]: continuing a run
//!   safely; [`snapshot`]: the run's copy of its preset file; [`inputs`]: the run's record of
//!   the presets and teachers its recipe names, which a resume is held to; [`crash`]: the kill
//!   tests' fault injection.
//! - [`evaluate`]: a checkpoint as a policy, evaluated on a preset.
//! - [`kickstart`]: a run's teachers (one trained policy per preset it trains on).
//! - [`shipped`]: the policies built into the binary (`fairgrasp_policy::shipped`, re-exported).

pub mod checkpoint;
pub mod config;
pub mod crash;
pub mod error;
pub mod evaluate;
pub mod folder;
pub mod inputs;
pub mod kickstart;
pub mod metrics;
pub mod resume;
pub use fairgrasp_policy::recipe::snapshot;
pub use fairgrasp_policy::shipped;
pub mod tensorboard;
pub mod train;

pub use config::TrainConfig;
pub use error::TrainError;
