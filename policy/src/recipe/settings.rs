//! The recipe: every setting of a training run, as `assets/experiments/*.toml` and a run's
//! `config.toml` write them, and the env configurations it trains and is evaluated on (read
//! and checked in [`crate::recipe::read`]).

use fairgrasp_env::config::presets;
use fairgrasp_env::scenario::curriculum::CurriculumConfig;
use fairgrasp_env::{ArmSimulation, EnvConfig};
use serde::{Deserialize, Serialize};

use crate::agent::AgentConfig;
use crate::checkpoint::network::ModelConfig;
use crate::recipe::env::{EnvFor, preset_env, with_env_table};
use crate::recipe::kickstart::KickstartConfig;
use crate::recipe::ppo::PpoConfig;

/// Everything a training run needs; saved as `config.toml` in the run folder. Training
/// (`fairgrasp-rl`'s `TrainConfig` is this type), evaluation and Python read the same recipe.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Recipe {
    /// Environment preset (`fixed`, `sector`, `wide`, `full`, `hard`, …) or a .toml file; an
    /// old preset name is read as its current one ([`presets::RENAMED_PRESETS`]).
    #[serde(deserialize_with = "presets::deserialize_name")]
    pub preset: String,
    /// Presets trained on besides `preset`, for one policy of several families (a generalist):
    /// the envs take `preset`, `mix[0]`, `mix[1]`, … in turn, and the run's evaluations split
    /// their episodes over all of them in the same order. Empty (the default): `preset` only.
    #[serde(
        skip_serializing_if = "Vec::is_empty",
        deserialize_with = "presets::deserialize_names"
    )]
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

impl Recipe {
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
