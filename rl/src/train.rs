//! A training run: config in, run folder out (`config.toml`, `metrics.csv`,
//! `checkpoints/latest`, `checkpoints/best`, `eval.json`); resumable after Ctrl-C or a kill.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use burn::tensor::Device;
use fairgrasp_env::curriculum::{Curriculum, CurriculumConfig};
use fairgrasp_env::policy::EvalReport;
use fairgrasp_env::presets;
use fairgrasp_env::randomize::scenario_set;
use fairgrasp_env::trajectory::write_atomic;
use fairgrasp_env::{ArmModelKind, EnvConfig, GraspEnv};
use serde::{Deserialize, Serialize};

use crate::agent::{ACT_DIM, AgentConfig};
use crate::checkpoint::{self, CheckpointMeta};
pub use crate::evaluate::{agent_policy, evaluate_model};
use crate::grasp_env::GraspVecEnv;
use crate::model::{ActorCritic, ModelConfig};
use crate::normalizer::RunningNorm;
use crate::ppo::{Ppo, PpoConfig, UpdateStats};

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
    /// Stage the randomisation with the curriculum (fixed → position → yaw → friction/mass).
    pub curriculum: Option<CurriculumConfig>,
    pub agent: AgentConfig,
    pub model: ModelConfig,
    pub ppo: PpoConfig,
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
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> TrainError + '_ {
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
        self.env_config().map(|_| ()).map_err(|e| e.to_string())
    }

    /// The environment configuration of the preset and arm.
    pub fn env_config(&self) -> Result<EnvConfig, fairgrasp_env::ConfigError> {
        let mut env = presets::load(&self.preset)?;
        env.arm.model = self.arm;
        Ok(env)
    }
}

/// One row of `metrics.csv`.
pub const METRICS_HEADER: &str = "update,timesteps,wall_time_s,episodes,episode_return,success_rate,episode_length,policy_loss,value_loss,entropy,approx_kl,clip_fraction,explained_variance,learning_rate,stage,eval_success_rate";

fn metrics_row(
    update: u64,
    timesteps: u64,
    wall: f64,
    s: &UpdateStats,
    stage: usize,
    eval: Option<f64>,
) -> String {
    let n = s.episodes.len().max(1) as f64;
    let mean = |f: &dyn Fn(&crate::vec_api::EpisodeStats) -> f64| {
        s.episodes.iter().map(f).sum::<f64>() / n
    };
    format!(
        "{update},{timesteps},{wall:.2},{},{:.4},{:.4},{:.2},{:.6},{:.6},{:.5},{:.6},{:.4},{:.4},{:.3e},{stage},{}",
        s.episodes.len(),
        mean(&|e| e.episode_return as f64),
        mean(&|e| e.success as u8 as f64),
        mean(&|e| e.length as f64),
        s.policy_loss,
        s.value_loss,
        s.entropy,
        s.approx_kl,
        s.clip_fraction,
        s.explained_variance,
        s.learning_rate,
        eval.map_or(String::new(), |e| format!("{e:.4}")),
    )
}

/// Progress of a run, reported after every update.
pub struct Progress<'a> {
    pub timesteps: u64,
    pub total: u64,
    pub stats: &'a UpdateStats,
    pub stage: usize,
    pub eval: Option<f64>,
}

/// Trains (or resumes) in `run_dir`; `report` is called after every update.
pub fn train(
    config: &TrainConfig,
    run_dir: &Path,
    resume: bool,
    report: &mut dyn FnMut(Progress),
) -> Result<EvalReport, TrainError> {
    config.validate().map_err(TrainError::Config)?;
    std::fs::create_dir_all(run_dir.join("checkpoints")).map_err(io(run_dir))?;
    let latest = run_dir.join("checkpoints/latest");
    let best_dir = run_dir.join("checkpoints/best");
    let metrics_path = run_dir.join("metrics.csv");
    let device = Device::flex().autodiff();
    device.seed(config.seed);
    let env_config = config
        .env_config()
        .map_err(|e| TrainError::Config(e.to_string()))?;
    let input_dim = config.agent.input_dim();

    let (mut meta, model, optimizer_from) = if resume {
        let (meta, model) = checkpoint::load_model(&latest, &device)?;
        if meta.input_dim != input_dim {
            return Err(TrainError::Config(format!(
                "the checkpoint's input size {} differs from this config's {input_dim}",
                meta.input_dim
            )));
        }
        (meta, model, Some(latest.clone()))
    } else {
        write_atomic(
            &run_dir.join("config.toml"),
            toml::to_string_pretty(config)
                .expect("serialisable")
                .as_bytes(),
        )
        .map_err(io(run_dir))?;
        write_atomic(&metrics_path, format!("{METRICS_HEADER}\n").as_bytes())
            .map_err(io(run_dir))?;
        let meta = CheckpointMeta {
            version: 1,
            input_dim,
            act_dim: ACT_DIM,
            model: config.model.clone(),
            agent: config.agent.clone(),
            obs_norm: RunningNorm::new(input_dim, config.ppo.norm_obs),
            timesteps: 0,
            updates: 0,
            wall_time_s: 0.0,
            eval_success_rate: None,
        };
        (
            meta,
            ActorCritic::new(input_dim, ACT_DIM, &config.model, &device),
            None,
        )
    };
    // Fail here, with the reason, rather than inside the rollout if no scenario can be drawn.
    let probe = GraspEnv::new(env_config.clone())?;
    scenario_set(
        &env_config,
        probe.model(),
        probe.base_in_world(),
        config.seed,
        1,
    )
    .map_err(|e| TrainError::Config(format!("preset {}: {e}", config.preset)))?;
    let episode_seed = config
        .seed
        .wrapping_mul(7_919)
        .wrapping_add(meta.updates * 1_000);
    let mut env = GraspVecEnv::new(
        &env_config,
        config.agent.clone(),
        config.n_envs,
        config.threads,
        episode_seed,
    )?;
    let mut ppo = Ppo::new(
        config.ppo.clone(),
        model,
        meta.obs_norm.clone(),
        device,
        config.seed.wrapping_add(meta.updates),
    );
    if let Some(dir) = optimizer_from {
        ppo.optimizer = checkpoint::load_optimizer(&dir, ppo.optimizer)?;
    }
    let mut curriculum = config
        .curriculum
        .clone()
        .map(|c| Curriculum::new(c, env_config.randomization.clone()));
    let per_update = (config.ppo.n_steps * config.n_envs) as u64;
    let start = Instant::now();
    let wall_before = meta.wall_time_s;
    let mut best = meta.eval_success_rate.unwrap_or(-1.0);
    let mut last_report = None;
    let out_of_time = |start: &Instant| {
        config
            .max_wall_time_s
            .is_some_and(|t| start.elapsed().as_secs_f64() >= t)
    };
    while meta.timesteps < config.total_timesteps && !out_of_time(&start) {
        if let Some(c) = &curriculum {
            env.inner_mut().set_randomization(&c.randomization())?;
        }
        let frozen_actor = meta.updates < config.critic_warmup_updates;
        let actor_before = frozen_actor.then(|| ppo.model.clone());
        let stats = ppo.iterate(
            &mut env,
            meta.timesteps as f64 / config.total_timesteps as f64,
        );
        if let Some(before) = actor_before {
            ppo.model = before.with_critic_of(ppo.model.clone());
        }
        meta.timesteps += per_update;
        meta.updates += 1;
        meta.wall_time_s = wall_before + start.elapsed().as_secs_f64();
        meta.obs_norm = ppo.obs_norm.clone();
        if let Some(c) = &mut curriculum {
            for e in &stats.episodes {
                c.record(e.success);
            }
        }
        let eval = if config.eval_every > 0
            && (meta.updates % config.eval_every == 0 || meta.timesteps >= config.total_timesteps)
        {
            let r = evaluate_model(config, &meta, &ppo.model, config.eval_episodes)?;
            meta.eval_success_rate = Some(r.success_rate);
            if r.success_rate > best {
                best = r.success_rate;
                checkpoint::save(&best_dir, &meta, &ppo.model, None)?;
            }
            let json = serde_json::to_vec_pretty(&r).expect("serialisable");
            write_atomic(&run_dir.join("eval.json"), &json).map_err(io(run_dir))?;
            last_report = Some(r.clone());
            Some(r.success_rate)
        } else {
            None
        };
        checkpoint::save(&latest, &meta, &ppo.model, Some(&ppo.optimizer))?;
        let stage = curriculum.as_ref().map_or(0, Curriculum::stage);
        let row = metrics_row(
            meta.updates,
            meta.timesteps,
            meta.wall_time_s,
            &stats,
            stage,
            eval,
        );
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&metrics_path)
            .map_err(io(&metrics_path))?;
        writeln!(f, "{row}").map_err(io(&metrics_path))?;
        report(Progress {
            timesteps: meta.timesteps,
            total: config.total_timesteps,
            stats: &stats,
            stage,
            eval,
        });
    }
    match last_report {
        Some(r) => Ok(r),
        None => evaluate_model(config, &meta, &ppo.model, config.eval_episodes),
    }
}

/// The run folder's latest checkpoint.
pub fn latest_checkpoint(run_dir: &Path) -> PathBuf {
    run_dir.join("checkpoints/latest")
}
