//! A training run's configuration (`config.toml` of a run folder) and the errors of a run.

use std::path::Path;

use fairgrasp_env::curriculum::CurriculumConfig;
use fairgrasp_env::presets;
use fairgrasp_env::{ArmModelKind, EnvConfig};
use serde::{Deserialize, Serialize};

use crate::agent::AgentConfig;
use crate::checkpoint;
use crate::model::ModelConfig;
use crate::ppo::PpoConfig;

/// Everything a training run needs; saved as `config.toml` in the run folder.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrainConfig {
    /// Environment preset (`fixed`, `seed`, `wide`, `full`, `hard`) or a .toml file.
    pub preset: String,
    /// Arm simulation.
    pub arm: ArmModelKind,
    /// Seed of the network initialisation, the sampling and the episodes.
    pub seed: u64,
    /// Environment steps to train for.
    pub total_timesteps: u64,
    /// Stop earlier once this much wall-clock time has passed in this invocation [s] (for
    /// comparisons at an equal time budget); None = no limit.
    pub max_wall_time_s: Option<f64>,
    /// Parallel environments.
    pub n_envs: usize,
    /// Threads stepping them.
    pub threads: usize,
    /// Evaluate (deterministic, on a fixed scenario set) every this many updates; 0 = never.
    pub eval_every: u64,
    /// Scenarios per evaluation.
    pub eval_episodes: usize,
    /// Updates at the start that train only the critic (the actor is frozen).
    pub critic_warmup_updates: u64,
    /// Stage the randomisation with the curriculum (fixed → [narrowed sectors →] position → yaw →
    /// friction/mass).
    pub curriculum: Option<CurriculumConfig>,
    pub agent: AgentConfig,
    pub model: ModelConfig,
    pub ppo: PpoConfig,
    /// Settings laid over the preset's env configuration for training only, as in an env
    /// config file (e.g. `[env.task] reward = "staged"`, `terminate_on_collision = false`).
    /// Evaluations use the preset as it is: the success criterion never changes.
    pub env: Option<toml::Table>,
}

/// Lays `top` over `base`: tables merge key by key, any other value replaces.
fn overlay(base: &mut toml::Table, top: &toml::Table) {
    for (key, value) in top {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(t)) => overlay(b, t),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

impl Default for TrainConfig {
    fn default() -> Self {
        Self {
            preset: "hard".into(),
            arm: ArmModelKind::Servo,
            seed: 0,
            total_timesteps: 200_000,
            max_wall_time_s: None,
            n_envs: 4,
            threads: 2,
            eval_every: 10,
            eval_episodes: 50,
            critic_warmup_updates: 0,
            curriculum: None,
            env: None,
            agent: AgentConfig::default(),
            model: ModelConfig {
                log_std_init: -1.0,
                zero_actor_output: true,
                ..ModelConfig::default()
            },
            ppo: PpoConfig {
                n_steps: 512,
                ..PpoConfig::default()
            },
        }
    }
}

/// Why a run could not start or go on.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    #[error("{0}")]
    Config(String),
    #[error(transparent)]
    Checkpoint(#[from] checkpoint::CheckpointError),
    #[error(transparent)]
    Env(#[from] fairgrasp_env::EnvError),
    #[error(
        "update {update} failed: {source}; checkpoints/latest keeps the last good network (update {last_good})"
    )]
    Update {
        /// The update that failed (1 = the first of this run folder).
        update: u64,
        /// The update `checkpoints/latest` holds.
        last_good: u64,
        source: Box<TrainError>,
    },
    #[error(transparent)]
    Ppo(#[from] crate::ppo::PpoError),
    #[error(transparent)]
    VecEnv(#[from] crate::vec_api::VecEnvError),
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

pub(crate) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> TrainError + '_ {
    move |source| TrainError::Io {
        path: path.display().to_string(),
        source,
    }
}

impl TrainConfig {
    /// Reads and checks a TOML file.
    pub fn from_toml_file(path: &Path) -> Result<Self, TrainError> {
        let text = std::fs::read_to_string(path).map_err(io(path))?;
        let config: TrainConfig = toml::from_str(&text)
            .map_err(|e| TrainError::Config(format!("{}: {e}", path.display())))?;
        config
            .validate()
            .map_err(|e| TrainError::Config(format!("{}: {e}", path.display())))?;
        Ok(config)
    }

    /// Checks every part; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        if self.n_envs == 0 || self.threads == 0 {
            return Err(format!(
                "n_envs = {}, threads = {}: both must be at least 1",
                self.n_envs, self.threads
            ));
        }
        if self.model.hidden.is_empty() || self.model.hidden.contains(&0) {
            return Err(format!(
                "model.hidden = {:?}: give one or more non-zero layer widths",
                self.model.hidden
            ));
        }
        if self.agent.residual_scale.is_nan() || self.agent.residual_scale <= 0.0 {
            return Err(format!(
                "agent.residual_scale = {}: must be positive",
                self.agent.residual_scale
            ));
        }
        self.ppo
            .validate(self.n_envs)
            .map_err(|e| format!("ppo: {e}"))?;
        if let Some(c) = &self.curriculum {
            c.validate()?;
        }
        let env = self.training_env_config().map_err(|e| e.to_string())?;
        if env.arm.action_space != fairgrasp_env::config::ActionSpace::Joint {
            return Err(
                "[env.arm] action_space must stay \"joint\" for an agent: choose the agent's action with [agent] action_space (evaluations would not see an env override)"
                    .into(),
            );
        }
        Ok(())
    }

    /// The environment configuration of the preset and arm (what evaluations use).
    pub fn env_config(&self) -> Result<EnvConfig, fairgrasp_env::ConfigError> {
        let mut env = presets::load(&self.preset)?;
        env.arm.model = self.arm;
        Ok(env)
    }

    /// The environment configuration training steps: [`TrainConfig::env_config`] with the
    /// `[env]` overrides laid over it, validated.
    pub fn training_env_config(&self) -> Result<EnvConfig, fairgrasp_env::ConfigError> {
        let env = self.env_config()?;
        let Some(overrides) = &self.env else {
            return Ok(env);
        };
        let invalid = |message: String| fairgrasp_env::ConfigError::File {
            path: "[env] of the training config".into(),
            message,
        };
        let mut table = toml::Table::try_from(&env).map_err(|e| invalid(e.to_string()))?;
        overlay(&mut table, overrides);
        let text = toml::to_string(&table).map_err(|e| invalid(e.to_string()))?;
        EnvConfig::from_toml_str(&text).map_err(|e| invalid(e.to_string()))
    }
}
