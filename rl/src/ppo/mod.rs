//! The PPO algorithm and nothing about grasping: the actor-critic network and its
//! initialisation, the policy's Gaussian, rollouts and GAE, the losses, the update loop, and
//! what PPO needs from an environment ([`vec_api`]). Imports nothing from the rest of the crate,
//! so the agents and runs build on it, never the other way round.
//!
//! - [`algorithm`]: the PPO loop, CleanRL style; [`loss`]: its losses and ratio diagnostics;
//!   [`config`] and [`error`]: its settings and why an iteration stops.
//! - [`model`]: the actor-critic MLPs; [`init`]: their weights from the run's own generator;
//!   [`gaussian`]: the policy's distribution, its one log-probability.
//! - [`rollout`]: the rollout buffer; [`gae`]: advantages, normalisation, explained variance;
//!   [`normalizer`]: running observation statistics.
//! - [`vec_api`]: the environment interface; [`point_mass`]: a small task PPO must solve;
//!   [`free_env`]: one that costs nothing (for timing PPO alone).
//! - [`teacher`]: kickstarting, a term that pulls the policy towards teachers' actions.

pub mod algorithm;
pub use fairgrasp_policy::recipe::ppo as config;
pub mod error;
pub mod free_env;
pub mod gae;
pub mod gaussian;
pub mod init;
pub mod loss;
pub mod model;
pub mod normalizer;
pub mod point_mass;
pub mod rollout;
pub mod teacher;
pub mod vec_api;

pub use algorithm::{Ppo, UpdateStats, adam};
pub use config::{PpoConfig, PpoConfigError};
pub use error::PpoError;
pub use loss::{RatioDiagnostics, clipped_surrogate, ratio_diagnostics, value_loss};
