//! Why a training run could not start or go on.

use std::path::Path;

/// Why a run could not start or go on.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    #[error("{0}")]
    Config(String),
    #[error(transparent)]
    Checkpoint(#[from] crate::run::checkpoint::CheckpointError),
    #[error(transparent)]
    Env(#[from] fairgrasp_env::EnvError),
    #[error(
        "update {update} failed: {cause}; checkpoints/latest keeps the last good network (update {last_good}); continue with --resume (after a divergence: lower learning_rate first and add --accept-config-changes)"
    )]
    Update {
        /// The update that failed (1 = the first of this run folder).
        update: u64,
        /// The update `checkpoints/latest` holds.
        last_good: u64,
        /// What went wrong (in the message, not a separate `source`, so it is printed once).
        cause: Box<TrainError>,
    },
    #[error(transparent)]
    Ppo(#[from] crate::ppo::PpoError),
    #[error(transparent)]
    VecEnv(#[from] crate::ppo::vec_api::VecEnvError),
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

impl From<fairgrasp_policy::recipe::RecipeError> for TrainError {
    fn from(e: fairgrasp_policy::recipe::RecipeError) -> Self {
        match e {
            fairgrasp_policy::recipe::RecipeError::Io { path, source } => {
                TrainError::Io { path, source }
            }
            fairgrasp_policy::recipe::RecipeError::Invalid(message) => TrainError::Config(message),
        }
    }
}

pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> TrainError + '_ {
    move |source| TrainError::Io {
        path: path.display().to_string(),
        source,
    }
}
