//! The recipe: every setting of a training run, as `assets/experiments/*.toml` and a run's
//! `config.toml` write them; read, checked, and the env configurations it trains and is
//! evaluated on.

use std::path::Path;

use fairgrasp_env::config::toml_lines;
use fairgrasp_env::scenario::curriculum::CurriculumConfig;
use fairgrasp_env::{ArmSimulation, EnvConfig};
use serde::{Deserialize, Serialize};

use crate::agent::AgentConfig;
use crate::checkpoint::network::ModelConfig;
pub use crate::checkpoint::verify::MAX_TIMESTEPS;
use crate::recipe::env::{ENV_OVERRIDES, EnvFor, check_agent_env, preset_env, with_env_table};
use crate::recipe::kickstart::KickstartConfig;
use crate::recipe::ppo::PpoConfig;
use crate::recipe::snapshot::env_snapshot_of;

/// The most parallel environments a run may step (each holds a physics world, ~1 MB).
pub const MAX_ENVS: usize = 4096;
/// The most threads a run may step them on.
pub const MAX_THREADS: usize = 256;
/// The most scenarios per evaluation.
pub const MAX_EVAL_EPISODES: usize = 100_000;

/// Everything a training run needs; saved as `config.toml` in the run folder. Training
/// (`fairgrasp-rl`'s `TrainConfig` is this type), evaluation and Python read the same recipe.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Recipe {
    /// Environment preset (`fixed`, `seed`, `wide`, `full`, `hard`) or a .toml file.
    pub preset: String,
    /// Presets trained on besides `preset`, for one policy of several families (a generalist):
    /// the envs take `preset`, `mix[0]`, `mix[1]`, … in turn, and the run's evaluations split
    /// their episodes over all of them in the same order. Empty (the default): `preset` only.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub mix: Vec<String>,
    /// Arm simulation.
    pub arm: ArmSimulation,
    /// Seed of the network initialisation, the sampling and the episodes.
    pub seed: u64,
    /// Environment steps to train for.
    pub total_timesteps: u64,
    /// Stop earlier once this much wall-clock time has passed in this invocation \[s\] (for
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
    /// Teachers the policy is also pulled towards, one per preset ([`crate::recipe::kickstart`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kickstart: Option<KickstartConfig>,
    /// Settings laid over the preset's env configuration for training only, as in an env
    /// config file (e.g. `[env.task] reward = "staged"`, `terminate_on_collision = false`).
    /// Evaluations use the preset as it is: the success criterion never changes.
    pub env: Option<toml::Table>,
    /// The run folder's copy of a preset file (`RUN/env.toml`), which a resumed run trains on
    /// instead of `preset` (see [`crate::recipe::snapshot`]); not saved.
    #[serde(skip)]
    pub env_snapshot: Option<std::path::PathBuf>,
}

impl Default for Recipe {
    fn default() -> Self {
        Self {
            preset: "hard".into(),
            mix: Vec::new(),
            arm: ArmSimulation::Servo,
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
            env_snapshot: None,
            kickstart: None,
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
        crate::recipe::contradictions::check(self)
    }

    /// The env configuration of every preset the recipe trains on, `preset`'s (or, resuming,
    /// the run's copy of it) then each of `mix`'s, with the recipe's arm: as they are
    /// ([`EnvFor::Evaluation`]) or with the `[env]` table laid over each and validated
    /// ([`EnvFor::Training`]). The message of a `mix` preset that does not load names it.
    pub fn env_configs(&self, purpose: EnvFor) -> Result<Vec<EnvConfig>, String> {
        let env_of = |preset: &str| {
            let env = preset_env(preset, self.arm)?;
            match purpose {
                EnvFor::Evaluation => Ok(env),
                EnvFor::Training => with_env_table(env, self.env.as_ref()),
            }
        };
        let mut all = vec![env_of(&self.env_preset()).map_err(|e| e.to_string())?];
        for p in &self.mix {
            all.push(env_of(p).map_err(|e| format!("mix: {p}: {e}"))?);
        }
        Ok(all)
    }

    /// The preset environments are built from: the run's copy of a preset file when resuming,
    /// else `preset`.
    pub fn env_preset(&self) -> String {
        match &self.env_snapshot {
            Some(p) => p.to_string_lossy().into_owned(),
            None => self.preset.clone(),
        }
    }
}
