//! Why a PPO iteration stops: environment errors and divergence (non-finite outputs, losses or
//! parameters), each naming what was found.

use crate::ppo::vec_api::VecEnvError;

/// Why a PPO iteration stopped.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PpoError {
    #[error(transparent)]
    Env(#[from] VecEnvError),
    #[error(
        "the network's {what} for environment {env} is {value}, not finite: the policy diverged (a lower learning_rate may help)"
    )]
    NonFiniteOutput {
        what: &'static str,
        env: usize,
        value: f32,
    },
    #[error(
        "the update made the network's parameters non-finite: the policy diverged (a lower learning_rate may help)"
    )]
    NonFiniteParameters,
    #[error(
        "the update's {what} is {value}, not finite: the policy diverged (a lower learning_rate may help)"
    )]
    NonFiniteLoss { what: &'static str, value: f32 },
    #[error("reading a tensor: {0}")]
    Tensor(String),
}

/// The first non-finite network output of `[env][dim]` rows, as an error.
pub(crate) fn finite_output(
    values: &[f32],
    dim: usize,
    what: &'static str,
) -> Result<(), PpoError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(PpoError::NonFiniteOutput {
            what,
            env: i / dim.max(1),
            value: values[i],
        }),
    }
}
