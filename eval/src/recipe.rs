//! A training recipe (`assets/experiments/*.toml`, a run's `config.toml`) as the env sees it:
//! which preset and arm, the `[env]` settings laid over the preset for training only, the
//! agent and the curriculum. The trainer (`fairgrasp-rl`) and Python read the env a recipe
//! trains on from here, so both meet the same env.

use std::path::Path;

use fairgrasp_env::config::{presets, toml_lines};
use fairgrasp_env::scenario::curriculum::CurriculumConfig;
use fairgrasp_env::{ArmSimulation, ConfigError, EnvConfig};
use serde::Deserialize;

use crate::agent::AgentConfig;

/// The env-facing part of a training config (its other keys — network, PPO, run length — are
/// the trainer's and are ignored here).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(default)]
pub struct Recipe {
    /// Environment preset name or a .toml file.
    pub preset: String,
    pub arm: ArmSimulation,
    pub agent: AgentConfig,
    pub curriculum: Option<CurriculumConfig>,
    /// Settings laid over the preset's env configuration for training only.
    pub env: Option<toml::Table>,
}

impl Default for Recipe {
    fn default() -> Self {
        Self {
            preset: "hard".into(),
            arm: ArmSimulation::Servo,
            agent: AgentConfig::default(),
            curriculum: None,
            env: None,
        }
    }
}

/// Lays `top` over `base`: tables merge key by key, any other value replaces.
pub fn overlay(base: &mut toml::Table, top: &toml::Table) {
    for (key, value) in top {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(t)) => overlay(b, t),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

impl Recipe {
    /// The keys a recipe's env-facing part has (what [`Recipe::with_overrides`] accepts).
    pub const KEYS: [&'static str; 5] = ["preset", "arm", "agent", "curriculum", "env"];

    /// The recipe of a training config's text (`what` names it in errors) with `overrides`
    /// laid over its env-facing part: each override's key must be one of [`Recipe::KEYS`];
    /// a table merges into the recipe's table key by key (`env = {task = {max_steps = 50}}`
    /// changes that one setting), any other value replaces, and a key in `remove` is dropped
    /// (`curriculum`: no curriculum; `env`: no training-only settings, the env evaluations
    /// use). A misspelt key is refused with the list of valid ones.
    pub fn with_overrides(
        text: &str,
        what: &str,
        overrides: &toml::Table,
        remove: &[String],
    ) -> Result<Self, ConfigError> {
        let file = |message: String| ConfigError::File {
            path: what.to_string(),
            message,
        };
        if let Some(bad) = overrides
            .keys()
            .chain(remove)
            .find(|k| !Self::KEYS.contains(&k.as_str()))
        {
            return Err(file(format!(
                "unknown override `{bad}`: the valid keys are {}",
                Self::KEYS.join(", ")
            )));
        }
        let mut table: toml::Table = toml::from_str(text).map_err(|e| {
            file(fairgrasp_env::config::validate::toml_error_message(
                text, &e,
            ))
        })?;
        table.retain(|k, _| Self::KEYS.contains(&AsRef::<str>::as_ref(k)));
        for key in remove {
            table.remove(key);
        }
        overlay(&mut table, overrides);
        let recipe: Recipe = toml::Value::Table(table)
            .try_into()
            .map_err(|e: toml::de::Error| file(e.to_string()))?;
        if let Some(c) = &recipe.curriculum {
            c.validate().map_err(file)?;
        }
        Ok(recipe)
    }

    /// Reads the env-facing part of a training config file.
    pub fn from_toml_file(path: &Path) -> Result<Self, ConfigError> {
        let file = |message: String| ConfigError::File {
            path: path.display().to_string(),
            message,
        };
        let text =
            fairgrasp_types::fs::read_text_bounded(path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
                .map_err(|e| file(e.to_string()))?;
        toml::from_str(&text).map_err(|e| {
            file(fairgrasp_env::config::validate::toml_error_message(
                &text, &e,
            ))
        })
    }

    /// The env configuration evaluations use: the preset as it is, with the recipe's arm.
    pub fn env_config(&self) -> Result<EnvConfig, ConfigError> {
        env_config(&self.preset, self.arm)
    }

    /// The env configuration training steps: [`Recipe::env_config`] with the `[env]`
    /// overrides laid over it, validated.
    pub fn training_env_config(&self) -> Result<EnvConfig, ConfigError> {
        training_env_config(&self.preset, self.arm, self.env.as_ref())
    }
}

/// Checks a recipe's training env against its agent: the env's own action must stay
/// `joint` (the agent chooses its action with `[agent] action_space`, and evaluations, which
/// use the preset as it is, would not see an `[env.arm]` override).
pub fn check_agent_env(training: &EnvConfig) -> Result<(), String> {
    if training.arm.action_space != fairgrasp_env::config::ActionSpace::Joint {
        return Err(
            "[env.arm] action_space must stay \"joint\" for an agent: choose the agent's action with [agent] action_space (evaluations would not see an env override)"
                .into(),
        );
    }
    Ok(())
}

/// The preset `preset` with arm simulation `arm`.
pub fn env_config(preset: &str, arm: ArmSimulation) -> Result<EnvConfig, ConfigError> {
    let mut env = presets::load(preset)?;
    env.arm.model = arm;
    Ok(env)
}

/// What an error of a training config's `[env]` table names as its place (the message goes on
/// with `: env.<field>`).
pub const ENV_OVERRIDES: &str = "[env] of the training config";

/// [`env_config`] with `overrides` (a training config's `[env]` table) laid over it, validated.
pub fn training_env_config(
    preset: &str,
    arm: ArmSimulation,
    overrides: Option<&toml::Table>,
) -> Result<EnvConfig, ConfigError> {
    let env = env_config(preset, arm)?;
    let Some(overrides) = overrides else {
        return Ok(env);
    };
    let invalid = |message: String| ConfigError::File {
        path: ENV_OVERRIDES.into(),
        message,
    };
    let mut table = toml::Table::try_from(&env).map_err(|e| invalid(e.to_string()))?;
    overlay(&mut table, overrides);
    let text = toml::to_string(&table).map_err(|e| invalid(e.to_string()))?;
    // Errors name the field as `env.<path>` (the merged text's lines are nobody's): the loader
    // of the training config finds the line the user wrote it on.
    let config: EnvConfig = toml::from_str(&text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
        let path = line.and_then(|l| toml_lines::path_at_line(&text, l));
        invalid(match path {
            Some(p) => format!("env.{p}: {}", e.message()),
            None => format!("env: {}", e.message()),
        })
    })?;
    config.validate().map_err(|e| match e {
        ConfigError::Invalid { field, value, rule } => {
            invalid(format!("env.{field} = {value}: {rule}"))
        }
        other => invalid(other.to_string()),
    })?;
    Ok(config)
}
