//! A recipe with keyword overrides laid over its env-facing keys, as Python builds an env from
//! a training recipe (`fairgrasp.make(recipe=..., curriculum=None, ...)`).

use fairgrasp_env::ConfigError;

use crate::recipe::contradictions;
use crate::recipe::env::overlay;
use crate::recipe::settings::Recipe;

impl Recipe {
    /// The keys of a recipe's env-facing part, the ones [`Recipe::with_overrides`] accepts.
    pub const OVERRIDE_KEYS: [&'static str; 5] = ["preset", "arm", "agent", "curriculum", "env"];

    /// The env-facing part of a training config's text (`what` names it in errors; the other
    /// keys — network, PPO, run length — are left at their defaults) with `overrides` laid over
    /// it: each override's key must be one of [`Recipe::OVERRIDE_KEYS`]; a table merges into
    /// the recipe's table key by key (`env = {task = {max_steps = 50}}` changes that one
    /// setting), any other value replaces, and a key in `remove` is dropped (`curriculum`: no
    /// curriculum; `env`: no training-only settings, the env evaluations use). A misspelt key
    /// is refused with the list of valid ones.
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
            .find(|k| !Self::OVERRIDE_KEYS.contains(&k.as_str()))
        {
            return Err(file(format!(
                "unknown override `{bad}`: the valid keys are {}",
                Self::OVERRIDE_KEYS.join(", ")
            )));
        }
        let mut table: toml::Table = toml::from_str(text).map_err(|e| {
            file(fairgrasp_env::config::validate::toml_error_message(
                text, &e,
            ))
        })?;
        table.retain(|k, _| Self::OVERRIDE_KEYS.contains(&AsRef::<str>::as_ref(k)));
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
        contradictions::check(&recipe).map_err(file)?;
        Ok(recipe)
    }
}
