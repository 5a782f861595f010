//! What a Python env is built from: a preset (or a whole env config) alone, or a training recipe
//! (`assets/experiments/*.toml`, a shipped name or a path) with keyword overrides, which brings
//! its agent and curriculum: the env the recipe trains on.

use fairgrasp_env::EnvConfig;
use fairgrasp_env::env::obs::OBS_NAMES;
use fairgrasp_env::env::spaces::{
    ACT_DIM, BoxSpace, action_space_of, f32_outward, observation_space,
};
use fairgrasp_env::scenario::curriculum::{Curriculum, CurriculumConfig};
use fairgrasp_policy::agent::AgentConfig;
use fairgrasp_policy::agent::env_agent::{output_names, script_input_bounds};
use fairgrasp_policy::recipe::{EnvFor, Recipe, check_agent_env};
use fairgrasp_policy::recipes;
use pyo3::prelude::*;

use crate::args::{env_config, value_error};

/// The env config, and for a recipe its agent and curriculum.
#[derive(Clone, Debug)]
pub(crate) struct Setup {
    /// The env as it is stepped (for a pure task-space agent, with its task-space action:
    /// [`AgentConfig::env_for`]).
    pub config: EnvConfig,
    /// The recipe's agent: the env's observation is its policy input and its action the
    /// policy's output. None: the env's own observation and action.
    pub agent: Option<AgentConfig>,
    pub curriculum: Option<CurriculumConfig>,
}

/// Overrides given as JSON (Python keyword arguments): a table to lay over the recipe, and the
/// top-level keys given as None (to drop). None below the top level is refused.
fn split_overrides(json: &str) -> PyResult<(toml::Table, Vec<String>)> {
    let value: serde_json::Value = serde_json::from_str(json).map_err(value_error)?;
    let serde_json::Value::Object(map) = value else {
        return Err(value_error("overrides must be keyword arguments"));
    };
    let mut table = toml::Table::new();
    let mut remove = Vec::new();
    for (key, v) in map {
        if v.is_null() {
            remove.push(key);
            continue;
        }
        let t: toml::Value = serde_json::from_value(v.clone()).map_err(|e| {
            value_error(format!(
                "override {key} = {v}: {e} (None is allowed only for a whole key, e.g. curriculum=None)"
            ))
        })?;
        table.insert(key, t);
    }
    Ok((table, remove))
}

impl Setup {
    /// From a preset name or .toml path (`config_toml`: a whole env config as TOML text
    /// instead), or from `recipe` with `overrides_json` (then `preset`, `arm`, `config_toml`
    /// must be left out: give `preset` and `arm` as overrides).
    pub fn new(
        preset: &str,
        arm: &str,
        config_toml: Option<&str>,
        recipe: Option<&str>,
        overrides_json: Option<&str>,
    ) -> PyResult<Self> {
        let Some(name) = recipe else {
            if overrides_json.is_some_and(|j| j.trim() != "{}") {
                return Err(value_error(
                    "overrides need a recipe: give recipe=... (or preset, arm, config_toml alone)",
                ));
            }
            return Ok(Self {
                config: env_config(preset, arm, config_toml)?,
                agent: None,
                curriculum: None,
            });
        };
        let (text, what) = recipes::text(name).map_err(value_error)?;
        let (overrides, remove) = split_overrides(overrides_json.unwrap_or("{}"))?;
        let r = Recipe::with_overrides(&text, &what, &overrides, &remove).map_err(value_error)?;
        let training = r
            .env_configs(EnvFor::Training)
            .map_err(value_error)?
            .swap_remove(0);
        check_agent_env(&training).map_err(|e| value_error(format!("{what}: {e}")))?;
        Ok(Self {
            config: r.agent.env_for(&training),
            agent: Some(r.agent),
            curriculum: r.curriculum,
        })
    }

    /// The curriculum's state at its first stage (its target: the config's randomisation).
    pub fn curriculum(&self) -> Option<Curriculum> {
        self.curriculum.clone().map(|c| {
            Curriculum::new(
                c,
                self.config.randomization.clone(),
                self.config.scene.cube_xy,
            )
        })
    }

    /// Values of the observation handed to Python (the agent's policy input).
    pub fn obs_dim(&self) -> usize {
        self.agent
            .as_ref()
            .map_or(fairgrasp_env::env::obs::OBS_DIM, AgentConfig::input_dim)
    }

    /// The observation space: the env's, then the script's part of a residual agent's input.
    pub fn observation_space(&self) -> (Vec<String>, Vec<f64>, Vec<f64>) {
        let cell = fairgrasp_env::cell::Cell::from_config(&self.config);
        let space = observation_space(&self.config, &cell.model);
        let mut names: Vec<String> = OBS_NAMES.iter().map(|n| n.to_string()).collect();
        let (mut low, mut high) = (space.low.clone(), space.high.clone());
        if let Some(agent) = &self.agent {
            names = agent.input_names(&self.config);
            let bound = |name: &str| {
                let i = OBS_NAMES.iter().position(|n| *n == name).unwrap_or(0);
                space.high[i..i + 3]
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()))
            };
            let object = bound("object_rel_tcp_x") + bound("tcp_x");
            for (lo, hi) in script_input_bounds(agent, &self.config, object) {
                let (l, h) = f32_outward(lo, hi);
                low.push(l);
                high.push(h);
            }
        }
        (names, low, high)
    }

    /// A space (names, low, high) as JSON.
    pub fn space_json(
        &self,
        (names, low, high): (Vec<String>, Vec<f64>, Vec<f64>),
    ) -> PyResult<String> {
        serde_json::to_string(&serde_json::json!({"names": names, "low": low, "high": high}))
            .map_err(value_error)
    }

    /// The action space: every entry in [−1, 1], named by what it commands.
    pub fn action_space(&self) -> (Vec<String>, Vec<f64>, Vec<f64>) {
        let env_space: BoxSpace = action_space_of(self.config.arm.action_space);
        let names = match &self.agent {
            Some(agent) => output_names(agent, &self.config),
            None => env_space.names.iter().map(|n| n.to_string()).collect(),
        };
        (names, vec![-1.0; ACT_DIM], vec![1.0; ACT_DIM])
    }
}

/// The names of the shipped training recipes.
#[pyfunction]
pub(crate) fn recipe_names() -> Vec<&'static str> {
    recipes::names()
}

/// The shipped recipe of the task-space residual for the shipped preset `preset`
/// (`fairgrasp_policy::recipes::task_residual_recipe`); an unknown preset is a ValueError.
#[pyfunction]
pub(crate) fn task_residual_recipe(preset: &str) -> PyResult<&'static str> {
    let config = fairgrasp_env::config::presets::load(preset).map_err(crate::args::value_error)?;
    Ok(recipes::task_residual_recipe(preset, config.task.kind))
}

/// The keys a recipe override may have.
#[pyfunction]
pub(crate) fn recipe_keys() -> Vec<&'static str> {
    Recipe::OVERRIDE_KEYS.to_vec()
}
