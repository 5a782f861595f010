//! PPO's hyper-parameters, with SB3's defaults, and the checks a run needs before it starts.

use serde::{Deserialize, Serialize};

/// Every PPO hyper-parameter; defaults are SB3's (the seed recipe's).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PpoConfig {
    /// Environment steps per environment per rollout (SB3 `n_steps`).
    pub n_steps: usize,
    /// Minibatch size (SB3 `batch_size`).
    pub batch_size: usize,
    /// Passes over each rollout.
    pub n_epochs: usize,
    /// Discount γ.
    pub gamma: f32,
    /// GAE λ.
    pub gae_lambda: f32,
    /// Surrogate clip ε.
    pub clip_coef: f32,
    /// Clip the value loss around the old values too.
    pub clip_vloss: bool,
    /// Entropy bonus coefficient.
    pub ent_coef: f32,
    /// Value loss coefficient.
    pub vf_coef: f32,
    /// Gradient-norm clip.
    pub max_grad_norm: f32,
    /// Adam learning rate.
    pub learning_rate: f64,
    /// Decay the learning rate linearly to 0 over training.
    pub anneal_lr: bool,
    /// Stop an update's epochs early once the approximate KL passes this.
    pub target_kl: Option<f32>,
    /// Normalise advantages per minibatch.
    pub norm_adv: bool,
    /// Normalise observations with running statistics.
    pub norm_obs: bool,
}

impl Default for PpoConfig {
    fn default() -> Self {
        Self {
            n_steps: 2048,
            batch_size: 64,
            n_epochs: 10,
            gamma: 0.99,
            gae_lambda: 0.95,
            clip_coef: 0.2,
            clip_vloss: false,
            ent_coef: 0.0,
            vf_coef: 0.5,
            max_grad_norm: 0.5,
            learning_rate: 3e-4,
            anneal_lr: false,
            target_kl: None,
            norm_adv: true,
            norm_obs: true,
        }
    }
}

/// A configuration PPO cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PpoConfigError {
    #[error(
        "the rollout (n_steps {n_steps} × {n_envs} envs = {rollout} samples) is not a multiple of batch_size {batch_size}: minibatches would be uneven (SB3 crashes here); choose n_steps or batch_size so that batch_size divides {rollout}"
    )]
    UnevenMinibatches {
        n_steps: usize,
        n_envs: usize,
        rollout: usize,
        batch_size: usize,
    },
    #[error("{field} = {value}: {rule}")]
    Invalid {
        field: &'static str,
        value: String,
        rule: &'static str,
    },
}

impl PpoConfig {
    /// Checks the configuration for `n_envs` environments.
    pub fn validate(&self, n_envs: usize) -> Result<(), PpoConfigError> {
        let bad = |field, value: String, rule| Err(PpoConfigError::Invalid { field, value, rule });
        if self.n_steps == 0 {
            return bad("n_steps", "0".into(), "must be at least 1");
        }
        if self.batch_size == 0 {
            return bad("batch_size", "0".into(), "must be at least 1");
        }
        if self.n_epochs == 0 {
            return bad("n_epochs", "0".into(), "must be at least 1");
        }
        if self.learning_rate.is_nan() || self.learning_rate <= 0.0 {
            return bad(
                "learning_rate",
                self.learning_rate.to_string(),
                "must be positive",
            );
        }
        if !(0.0..=1.0).contains(&self.gamma) || !(0.0..=1.0).contains(&self.gae_lambda) {
            return bad(
                "gamma/gae_lambda",
                format!("{}/{}", self.gamma, self.gae_lambda),
                "must be in [0, 1]",
            );
        }
        let rollout = self.n_steps * n_envs;
        if !rollout.is_multiple_of(self.batch_size) {
            return Err(PpoConfigError::UnevenMinibatches {
                n_steps: self.n_steps,
                n_envs,
                rollout,
                batch_size: self.batch_size,
            });
        }
        Ok(())
    }
}
