//! A recipe's `[ppo]` table: PPO's hyper-parameters, with SB3's defaults, and the checks a run
//! needs before it starts (the algorithm is `fairgrasp-rl`'s `ppo`).

use fairgrasp_env::config::{Bounds, SettingNumber, bounds_rule};
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
    /// With `anneal_lr`: the fraction of `total_timesteps`, in [0, 1), during which the
    /// learning rate stays at `learning_rate` before it falls linearly to 0 at the end (0, the
    /// default: from the first step, as SB3 and CleanRL anneal).
    pub anneal_from: f64,
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
            anneal_from: 0.0,
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
        /// What the value must be, e.g. `must be in (0, 1]`.
        rule: String,
    },
}

/// The largest rollout (n_steps × n_envs samples) a run may hold in memory: 2²² samples, about
/// 0.5 GB of observations and buffers on a laptop.
pub const MAX_ROLLOUT: usize = 1 << 22;

impl PpoConfig {
    /// The learning rate of the update at `progress` (the fraction of `total_timesteps` done,
    /// in [0, 1]): `learning_rate`, or with `anneal_lr` that rate until `anneal_from` and then
    /// falling linearly to 0 at `progress` 1.
    pub fn learning_rate_at(&self, progress: f64) -> f64 {
        if !self.anneal_lr {
            return self.learning_rate;
        }
        let left = (1.0 - progress) / (1.0 - self.anneal_from);
        self.learning_rate * left.clamp(0.0, 1.0)
    }

    /// Checks the configuration for `n_envs` environments: every number finite and in its
    /// range, the rollout's size overflow-checked and capped at [`MAX_ROLLOUT`].
    pub fn validate(&self, n_envs: usize) -> Result<(), PpoConfigError> {
        let count = Bounds::closed(1.0, 1e6);
        let unit_interval = Bounds::closed(0.0, 1.0);
        let weight = Bounds::closed(0.0, 100.0);
        in_bounds("n_steps", self.n_steps, count, "")?;
        in_bounds("batch_size", self.batch_size, count, "")?;
        in_bounds("n_epochs", self.n_epochs, Bounds::closed(1.0, 1000.0), "")?;
        in_bounds(
            "learning_rate",
            self.learning_rate,
            Bounds::above_to(0.0, 1.0),
            "(SB3's default 3e-4)",
        )?;
        in_bounds(
            "anneal_from",
            self.anneal_from,
            Bounds::from_below(0.0, 1.0),
            "(the fraction of training before the learning rate decays)",
        )?;
        in_bounds("gamma", self.gamma, unit_interval, "")?;
        in_bounds("gae_lambda", self.gae_lambda, unit_interval, "")?;
        in_bounds(
            "clip_coef",
            self.clip_coef,
            Bounds::above_to(0.0, 1.0),
            "(default 0.2)",
        )?;
        in_bounds("ent_coef", self.ent_coef, weight, "")?;
        in_bounds("vf_coef", self.vf_coef, weight, "")?;
        in_bounds(
            "max_grad_norm",
            self.max_grad_norm,
            Bounds::above_to(0.0, 1e6),
            "(default 0.5)",
        )?;
        if let Some(kl) = self.target_kl {
            in_bounds(
                "target_kl",
                kl,
                Bounds::above_to(0.0, 100.0),
                "(or left out for no early stop)",
            )?;
        }
        let rollout = self
            .n_steps
            .checked_mul(n_envs)
            .filter(|r| *r <= MAX_ROLLOUT);
        let Some(rollout) = rollout else {
            return Err(PpoConfigError::Invalid {
                field: "n_steps × n_envs",
                value: format!("{} × {}", self.n_steps, n_envs),
                rule: "must be at most 4194304 samples per rollout (2^22, about 0.5 GB)".into(),
            });
        };
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

/// `Ok` when `value` lies within `bounds`, else the refusal naming `field`, the value as written
/// and both bounds (then `note`).
fn in_bounds(
    field: &'static str,
    value: impl SettingNumber,
    bounds: Bounds,
    note: &'static str,
) -> Result<(), PpoConfigError> {
    if bounds.contains(value.as_f64()) {
        return Ok(());
    }
    Err(PpoConfigError::Invalid {
        field,
        value: format!("{value:?}"),
        rule: bounds_rule(&bounds, note),
    })
}
