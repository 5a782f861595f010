//! The env a recipe's preset gives: as it is for evaluations, or with the recipe's `[env]`
//! table laid over it for training ([`crate::recipe::Recipe::env_configs`] puts them together).

use fairgrasp_env::config::{presets, toml_lines};
use fairgrasp_env::{ArmSimulation, ConfigError, EnvConfig};

/// What a recipe's env configuration is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnvFor {
    /// The preset as it is (the success criterion never changes).
    Evaluation,
    /// The preset with the recipe's `[env]` table laid over it, validated.
    Training,
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
pub fn preset_env(preset: &str, arm: ArmSimulation) -> Result<EnvConfig, ConfigError> {
    let mut env = presets::load(preset)?;
    env.arm.model = arm;
    Ok(env)
}

/// What an error of a training config's `[env]` table names as its place (the message goes on
/// with `: env.<field>`).
pub const ENV_OVERRIDES: &str = "[env] of the training config";

/// `env` with `overrides` (a training config's `[env]` table) laid over it, validated.
pub fn with_env_table(
    env: EnvConfig,
    overrides: Option<&toml::Table>,
) -> Result<EnvConfig, ConfigError> {
    let Some(overrides) = overrides else {
        return Ok(env);
    };
    let invalid = |message: String| ConfigError::File {
        path: ENV_OVERRIDES.into(),
        message,
    };
    let mut table = toml::Table::try_from(&env).map_err(|e| invalid(e.to_string()))?;
    overlay(&mut table, overrides);
    // Every list whole, as a preset file's (a list longer than its field was read short).
    fairgrasp_env::config::lists::check_lists::<EnvConfig>(&table).map_err(|e| match e {
        ConfigError::Invalid { field, value, rule } => {
            invalid(format!("env.{field} = {value}: {rule}"))
        }
        other => invalid(other.to_string()),
    })?;
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
