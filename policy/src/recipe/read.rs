//! A recipe file read and checked: [`Recipe::from_toml_file`], [`Recipe::validate`] (every
//! number in its range, the tables' own rules, the env each preset gives, and no two settings
//! that contradict each other, [`crate::recipe::contradictions`]), and why a file is refused.

use std::path::Path;

use fairgrasp_env::config::toml_lines;

pub use crate::checkpoint::verify::MAX_TIMESTEPS;
use crate::recipe::contradictions;
use crate::recipe::env::{ENV_OVERRIDES, EnvFor, check_agent_env};
use crate::recipe::settings::Recipe;
use crate::recipe::snapshot::env_snapshot_of;

/// The most parallel environments a run may step (each holds a physics world, ~1 MB).
pub const MAX_ENVS: usize = 4096;
/// The most threads a run may step them on.
pub const MAX_THREADS: usize = 256;
/// The most scenarios per evaluation.
pub const MAX_EVAL_EPISODES: usize = 100_000;

/// Why a recipe file could not be read or is refused; the message names the file.
#[derive(Debug, thiserror::Error)]
pub enum RecipeError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{0}")]
    Invalid(String),
}

/// The old preset names ([`fairgrasp_env::config::presets::RENAMED_PRESETS`]) the recipe file
/// at `path` gives as its `preset` or in its `mix`, for a front end to note: the recipe loads
/// them as the current names. Empty if the file cannot be read or parsed (its loader says why).
pub fn old_preset_names_in(path: &Path) -> Vec<String> {
    let Ok(text) =
        fairgrasp_types::fs::read_text_bounded(path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
    else {
        return Vec::new();
    };
    let Ok(table) = toml::from_str::<toml::Table>(&text) else {
        return Vec::new();
    };
    let preset = table.get("preset").into_iter();
    let mix = table
        .get("mix")
        .and_then(toml::Value::as_array)
        .into_iter()
        .flatten();
    preset
        .chain(mix)
        .filter_map(toml::Value::as_str)
        .filter(|name| fairgrasp_env::config::presets::current_name(name).1)
        .map(String::from)
        .collect()
}

impl Recipe {
    /// Reads and checks a TOML file.
    pub fn from_toml_file(path: &Path) -> Result<Self, RecipeError> {
        Self::from_toml_file_in(path, None)
    }

    /// [`Recipe::from_toml_file`] for a resume of the run in `run_dir`: a preset file is
    /// taken from the run's copy of it (`env.toml`), wherever the command runs.
    pub fn from_toml_file_in(path: &Path, run_dir: Option<&Path>) -> Result<Self, RecipeError> {
        let text =
            fairgrasp_types::fs::read_text_bounded(path, fairgrasp_types::fs::MAX_CONFIG_BYTES)
                .map_err(|source| RecipeError::Io {
                    path: path.display().to_string(),
                    source,
                })?;
        let mut config: Recipe = toml::from_str(&text).map_err(|e| {
            let message = fairgrasp_env::config::validate::toml_error_message(&text, &e);
            RecipeError::Invalid(format!("{}: {message}", path.display()))
        })?;
        if let Some(dir) = run_dir {
            config.env_snapshot = env_snapshot_of(&config.preset, dir);
        }
        config.validate().map_err(|e| {
            // An error in the `[env]` overrides names its field as `env.<path>`: cite its line.
            let line = e
                .strip_prefix(ENV_OVERRIDES)
                .and_then(|rest| rest.strip_prefix(": "))
                .and_then(|rest| rest.split([' ', ':']).next())
                .and_then(|field| toml_lines::line_of_path(&text, field));
            match line {
                Some(l) => RecipeError::Invalid(format!("{}: line {l}: {e}", path.display())),
                None => RecipeError::Invalid(format!("{}: {e}", path.display())),
            }
        })?;
        Ok(config)
    }

    /// Checks every part; the message names the field, the value and the allowed range.
    pub fn validate(&self) -> Result<(), String> {
        if let Some((field, value, rule)) = fairgrasp_env::config::validate::first_bad_number(self)
        {
            return Err(format!("{field} = {value}: {rule}"));
        }
        if !(1..=MAX_ENVS).contains(&self.n_envs) {
            return Err(format!(
                "n_envs = {}: must be in 1..={MAX_ENVS}",
                self.n_envs
            ));
        }
        if !(1..=MAX_THREADS).contains(&self.threads) {
            return Err(format!(
                "threads = {}: must be in 1..={MAX_THREADS}",
                self.threads
            ));
        }
        if !(1..=MAX_TIMESTEPS).contains(&self.total_timesteps) {
            return Err(format!(
                "total_timesteps = {}: must be in 1..={MAX_TIMESTEPS}",
                self.total_timesteps
            ));
        }
        if let Some(t) = self.max_wall_time_s
            && (t.is_nan() || t <= 0.0 || t > 1e6)
        {
            return Err(format!(
                "max_wall_time_s = {t}: must be in (0, 1e6] seconds, or left out"
            ));
        }
        if !(1..=MAX_EVAL_EPISODES).contains(&self.eval_episodes) {
            return Err(format!(
                "eval_episodes = {}: must be in 1..={MAX_EVAL_EPISODES} (the run's evaluations and its final one)",
                self.eval_episodes
            ));
        }
        self.model.check()?;
        self.agent.check()?;
        self.ppo
            .validate(self.n_envs)
            .map_err(|e| format!("ppo: {e}"))?;
        if let Some(c) = &self.curriculum {
            c.validate()?;
        }
        if !self.mix.is_empty() {
            let presets = self.mix.len() + 1;
            if self.curriculum.is_some() {
                return Err("mix: a run on several presets cannot also have a [curriculum] (it stages one preset's randomisation)".into());
            }
            if self.n_envs < presets {
                return Err(format!(
                    "mix: {presets} presets need n_envs ≥ {presets} (one env each at least), got {}",
                    self.n_envs
                ));
            }
        }
        if let Some(k) = &self.kickstart {
            k.check(self.mix.len() + 1)?;
        }
        for env in self.env_configs(EnvFor::Training)? {
            check_agent_env(&env)?;
        }
        contradictions::check(self)
    }
}

/// Every leaf of a TOML value as `(dotted.path, value)`.
fn flatten(value: &toml::Value, path: &str, out: &mut Vec<(String, String)>) {
    match value {
        toml::Value::Table(t) => {
            for (k, v) in t {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                flatten(v, &p, out);
            }
        }
        other => out.push((path.to_string(), other.to_string())),
    }
}

/// One leaf in which two TOML values differ: its dotted path and its value in each (`(unset)`
/// where one of them has none).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeafChange {
    pub path: String,
    pub before: String,
    pub now: String,
}

impl std::fmt::Display for LeafChange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {} → {}", self.path, self.before, self.now)
    }
}

/// Every leaf in which `new` differs from `old` (two recipes, or two env configs, as TOML
/// values), in the order of the paths: how a resume names what changed since a run or a
/// tuning started.
pub fn leaf_differences(old: &toml::Value, new: &toml::Value) -> Vec<LeafChange> {
    let leaves = |v: &toml::Value| {
        let mut out = Vec::new();
        flatten(v, "", &mut out);
        out
    };
    let (old, new) = (leaves(old), leaves(new));
    let find = |list: &[(String, String)], key: &str| {
        list.iter()
            .find(|(k, _)| k == key)
            .map_or("(unset)".to_string(), |(_, v)| v.clone())
    };
    let mut keys: Vec<&String> = old.iter().chain(&new).map(|(k, _)| k).collect();
    keys.sort();
    keys.dedup();
    keys.into_iter()
        .filter_map(|k| {
            let (before, now) = (find(&old, k), find(&new, k));
            (before != now).then(|| LeafChange {
                path: k.clone(),
                before,
                now,
            })
        })
        .collect()
}
