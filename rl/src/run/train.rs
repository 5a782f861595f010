//! A training run: config in, run folder out (`config.toml`, `metrics.csv`, TensorBoard's
//! `events.out.tfevents.*`, `checkpoints/latest`, `checkpoints/best`, `eval.json`); resumable
//! after Ctrl-C or a kill.
//!
//! A fresh run saves its untrained network as `checkpoints/latest` (update 0) before the first
//! update, and `latest` is only ever replaced by a network whose parameters are finite: a run
//! that diverges or meets an environment fault stops with an error naming the update, and
//! `latest` still loads.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use burn::tensor::Device;
use fairgrasp_env::episode::EvalReport;
use fairgrasp_env::scenario::curriculum::Curriculum;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_policy::recipe::EnvFor;
use fairgrasp_types::write_atomic;

use crate::agent::grasp_agent::ACT_DIM;
use crate::agent::task_vec_env::TaskVecEnv;
use crate::ppo::model::ActorCritic;
use crate::ppo::teacher::Kickstart;
use crate::ppo::{Ppo, UpdateStats};
use crate::run::checkpoint::{self, CheckpointMeta};
pub use crate::run::config::TrainConfig;
use crate::run::crash;
pub use crate::run::error::TrainError;
use crate::run::error::io;
pub use crate::run::evaluate::{agent_policy, evaluate_model};
use crate::run::folder::{self, RunLock, Start, StartFlags};
use crate::run::kickstart;
use crate::run::metrics::{metrics_header, metrics_row};
use crate::run::resume::{self, ResumeOptions};
use crate::run::tensorboard::TensorBoardLog;

/// The bit every training episode's scenario seed has set (and no evaluation seed has).
pub const TRAINING_SEEDS: u64 = 1 << 63;

/// Progress of a run, reported after every update.
pub struct Progress<'a> {
    pub timesteps: u64,
    pub total: u64,
    pub stats: &'a UpdateStats,
    pub stage: usize,
    pub eval: Option<f64>,
    /// Environment steps per second of this update's rollout and learning.
    pub steps_per_second: f64,
}

/// A run in progress: its files, network, env and bookkeeping.
struct Run<'a> {
    config: &'a TrainConfig,
    run_dir: PathBuf,
    meta: CheckpointMeta,
    ppo: Ppo,
    env: TaskVecEnv,
    curriculum: Option<Curriculum>,
    /// Best evaluation success rate so far (-1 before any).
    best: f64,
    last_report: Option<EvalReport>,
    start: Instant,
    wall_before: f64,
    /// The update `checkpoints/latest` holds.
    saved_updates: u64,
    /// The run's TensorBoard event file (the same values as `metrics.csv`).
    tensorboard: TensorBoardLog,
    /// Held while the run trains: no second process trains into the folder.
    _lock: RunLock,
}

impl Run<'_> {
    fn latest(&self) -> PathBuf {
        self.run_dir.join("checkpoints/latest")
    }

    fn save_latest(&mut self) -> Result<(), TrainError> {
        checkpoint::save(
            &self.latest(),
            &self.meta,
            &self.ppo.model,
            Some(&self.ppo.optimizer),
        )?;
        self.saved_updates = self.meta.updates;
        Ok(())
    }

    /// One PPO update, its evaluation (when due), checkpoints and metrics row.
    fn update(&mut self, report: &mut dyn FnMut(Progress)) -> Result<(), TrainError> {
        let config = self.config;
        if let Some(c) = &self.curriculum {
            self.env.inner_mut().set_randomization(&c.randomization())?;
        }
        let frozen_actor = self.meta.updates < config.critic_warmup_updates;
        let actor_before = frozen_actor.then(|| self.ppo.model.clone());
        let progress = self.meta.timesteps as f64 / config.total_timesteps as f64;
        let iterate_start = Instant::now();
        let stats = self.ppo.iterate(&mut self.env, progress)?;
        let speed = (config.ppo.n_steps * config.n_envs) as f64
            / iterate_start.elapsed().as_secs_f64().max(1e-9);
        if let Some(before) = actor_before {
            self.ppo.model = before.with_critic_of(self.ppo.model.clone());
        }
        self.meta.timesteps += (config.ppo.n_steps * config.n_envs) as u64;
        self.meta.updates += 1;
        self.meta.wall_time_s = self.wall_before + self.start.elapsed().as_secs_f64();
        self.meta.obs_norm = self.ppo.obs_norm.clone();
        if let Some(c) = &mut self.curriculum {
            for e in &stats.episodes {
                c.record_at(e.success, e.object_xy);
            }
        }
        let due = config.eval_every > 0
            && (self.meta.updates.is_multiple_of(config.eval_every)
                || self.meta.timesteps >= config.total_timesteps);
        let eval = if due {
            let r = evaluate_model(config, &self.meta, &self.ppo.model, config.eval_episodes)?;
            // What counts: success within the takt on a task that runs on one (every success
            // counts on one that does not, so this is the success rate there).
            let score = r.within_takt_rate;
            self.meta.eval_success_rate = Some(score);
            if score > self.best {
                self.best = score;
                self.meta.best_eval_success_rate = Some(self.best);
                let best_dir = self.run_dir.join("checkpoints/best");
                checkpoint::save(&best_dir, &self.meta, &self.ppo.model, None)?;
            }
            let json = serde_json::to_vec_pretty(&r)
                .map_err(|e| TrainError::Config(format!("eval.json: {e}")))?;
            write_atomic(&self.run_dir.join("eval.json"), &json).map_err(io(&self.run_dir))?;
            let rate = score;
            self.last_report = Some(r);
            Some(rate)
        } else {
            None
        };
        // The row travels inside the checkpoint first, then into metrics.csv: a kill between
        // the two loses nothing (a resume restores the row from the checkpoint).
        let stage = self.curriculum.as_ref().map_or(0, Curriculum::stage);
        let m = &self.meta;
        let row = metrics_row(
            m.updates,
            m.timesteps,
            (m.wall_time_s, speed),
            &stats,
            stage,
            eval,
        );
        self.meta.metrics_row = Some(row.clone());
        self.meta.curriculum_stage = self.curriculum.as_ref().map(Curriculum::stage);
        let update = self.meta.updates;
        crash::point("before_checkpoint", update);
        self.save_latest()?;
        crash::point("before_row", update);
        let metrics_path = self.run_dir.join("metrics.csv");
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(&metrics_path)
            .map_err(io(&metrics_path))?;
        crash::torn_write("torn_row", update, &mut f, row.as_bytes());
        writeln!(f, "{row}").map_err(io(&metrics_path))?;
        f.sync_data().map_err(io(&metrics_path))?;
        crash::point("after_row", update);
        self.tensorboard.write_row(&row)?;
        report(Progress {
            timesteps: self.meta.timesteps,
            total: config.total_timesteps,
            stats: &stats,
            stage,
            eval,
            steps_per_second: speed,
        });
        Ok(())
    }
}

/// The network to start from: `latest` when resuming (with its meta and optimiser folder),
/// else a fresh one (and the run folder's `config.toml` and `metrics.csv` header).
fn start_from(
    config: &TrainConfig,
    run_dir: &Path,
    resume: bool,
    device: &Device,
) -> Result<(CheckpointMeta, ActorCritic, Option<PathBuf>), TrainError> {
    let latest = run_dir.join("checkpoints/latest");
    let input_dim = config.agent.input_dim();
    if resume {
        let (meta, model) = checkpoint::load_model(&latest, device)?;
        if meta.input_dim != input_dim {
            return Err(TrainError::Config(format!(
                "the checkpoint's input size {} differs from this config's {input_dim}",
                meta.input_dim
            )));
        }
        let (dropped, restored, missing) =
            resume::repair_metrics(run_dir, &meta, &metrics_header())?;
        if dropped + restored > 0 || missing > 0 {
            eprintln!(
                "note: metrics.csv repaired to match checkpoints/latest (update {}): {dropped} torn, unreadable or extra lines set aside in metrics.rejected.csv, {restored} restored from the checkpoint, {missing} earlier updates without a row",
                meta.updates
            );
        }
        return Ok((meta, model, Some(latest)));
    }
    let toml = toml::to_string_pretty(config)
        .map_err(|e| TrainError::Config(format!("config.toml: {e}")))?;
    write_atomic(&run_dir.join("config.toml"), toml.as_bytes()).map_err(io(run_dir))?;
    write_atomic(
        &run_dir.join("metrics.csv"),
        format!("{}\n", metrics_header()).as_bytes(),
    )
    .map_err(io(run_dir))?;
    let meta = CheckpointMeta::fresh(
        config.model.clone(),
        config.agent.clone(),
        config.ppo.norm_obs,
    );
    let model = ActorCritic::new(input_dim, ACT_DIM, &config.model, config.seed, device);
    Ok((meta, model, None))
}

/// Trains (or resumes) in `run_dir`; `report` is called after every update.
///
/// An error during an update ([`TrainError::Update`]) names the update and the one
/// `checkpoints/latest` still holds.
pub fn train(
    config: &TrainConfig,
    run_dir: &Path,
    resume: bool,
    report: &mut dyn FnMut(Progress),
) -> Result<EvalReport, TrainError> {
    let options = ResumeOptions {
        resume,
        ..ResumeOptions::default()
    };
    train_with(config, run_dir, options, report)
}

/// [`train`] with the resume options spelled out: a resume checks the config against the run's
/// `config.toml` (see [`crate::run::resume`]), repairs `metrics.csv` to match `checkpoints/latest`
/// and carries the best score over; a resume of a folder with no checkpoint starts fresh.
pub fn train_with(
    config: &TrainConfig,
    run_dir: &Path,
    options: ResumeOptions,
    report: &mut dyn FnMut(Progress),
) -> Result<EvalReport, TrainError> {
    // The teachers load before the run folder is touched: a wrong one changes nothing there.
    let kickstart = match &config.kickstart {
        Some(k) => {
            let envs = config
                .env_configs(EnvFor::Evaluation)
                .map_err(TrainError::Config)?;
            Some(kickstart::load(k, &config.agent, &envs)?)
        }
        None => None,
    };
    let (lock, start) = claim_run_folder(run_dir, options)?;
    let resume = start == Start::Resume;
    let config = &resume::config_for_run(config, run_dir, resume, options.accept_config_changes)?;
    let mut run = open_run(config, run_dir, resume, lock, kickstart)?;
    if !resume {
        run.save_latest()?;
    }
    let out_of_time = |start: &Instant| {
        config
            .max_wall_time_s
            .is_some_and(|t| start.elapsed().as_secs_f64() >= t)
    };
    while run.meta.timesteps < config.total_timesteps && !out_of_time(&run.start) {
        let update = run.saved_updates + 1;
        run.update(report).map_err(|e| TrainError::Update {
            update,
            last_good: run.saved_updates,
            cause: Box::new(e),
        })?;
    }
    match run.last_report {
        Some(r) => Ok(r),
        None => evaluate_model(config, &run.meta, &run.ppo.model, config.eval_episodes),
    }
}

/// Takes `run_dir` for this run: decides how to start (resume, fresh, or fresh after moving an
/// earlier run aside, per `options`) and holds the folder's lock. Returns the lock and the
/// decision, made again under the lock.
fn claim_run_folder(
    run_dir: &Path,
    options: ResumeOptions,
) -> Result<(RunLock, Start), TrainError> {
    let flags = StartFlags {
        resume: options.resume,
        force: options.force,
    };
    // Refused before anything is written (a foreign folder gets no lock file); decided again
    // under the lock, where no other process can change the folder.
    folder::decide(run_dir, flags)?;
    let mut lock = RunLock::acquire(run_dir)?;
    let start = folder::decide(run_dir, flags)?;
    if let Start::FreshAfterMovingAside(to) = &start {
        folder::move_aside(run_dir, to)?;
        eprintln!(
            "note: the run that was in {} is now in {}",
            run_dir.display(),
            to.display()
        );
        lock = RunLock::acquire(run_dir)?;
    }
    if let Some(pid) = &lock.stale_pid {
        eprintln!(
            "note: {} had a lock file of process {pid}, which ended without releasing it: taken over",
            run_dir.display()
        );
    }
    Ok((lock, start))
}

/// Sets up the run in the claimed `run_dir`: its network (fresh, or `latest` when `resume`),
/// TensorBoard log, training envs, PPO (with the optimiser's state when resuming, and the
/// `kickstart` teachers) and curriculum at the saved stage.
fn open_run<'a>(
    config: &'a TrainConfig,
    run_dir: &Path,
    resume: bool,
    lock: RunLock,
    kickstart: Option<Kickstart>,
) -> Result<Run<'a>, TrainError> {
    std::fs::create_dir_all(run_dir.join("checkpoints")).map_err(io(run_dir))?;
    let device = Device::flex().autodiff();
    let mixture = config
        .env_configs(EnvFor::Training)
        .map_err(TrainError::Config)?;
    let env_config = &mixture[0];
    let (meta, model, optimizer_from) = start_from(config, run_dir, resume, &device)?;
    let config_text = toml::to_string_pretty(config)
        .map_err(|e| TrainError::Config(format!("config.toml: {e}")))?;
    let tensorboard = TensorBoardLog::open(run_dir, &config_text, meta.timesteps)?;
    // Fail here, with the reason, rather than inside the rollout if no scenario can be drawn.
    env_config
        .validate()
        .map_err(fairgrasp_env::EnvError::from)?;
    scenario_set(env_config, config.seed, 1)
        .map_err(|e| TrainError::Config(format!("preset {}: {e}", config.preset)))?;
    let env = TaskVecEnv::mixed(
        &mixture,
        config.agent.clone(),
        config.n_envs,
        config.threads,
        training_episode_seed(config.seed, meta.updates),
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
    ppo.kickstart = kickstart;
    Ok(Run {
        config,
        run_dir: run_dir.to_path_buf(),
        curriculum: config.curriculum.clone().map(|c| {
            Curriculum::new(
                c,
                env_config.randomization.clone(),
                env_config.scene.cube_xy,
            )
            .at_stage(meta.curriculum_stage.unwrap_or(0))
        }),
        best: if resume {
            resume::best_so_far(run_dir, &meta)
        } else {
            -1.0
        },
        last_report: None,
        start: Instant::now(),
        wall_before: meta.wall_time_s,
        saved_updates: meta.updates,
        tensorboard,
        meta,
        ppo,
        env,
        _lock: lock,
    })
}

/// The first episode seed of the training envs after `updates` updates of a run seeded `seed`.
///
/// Training scenarios live in the upper half of the seed space ([`TRAINING_SEEDS`]); evaluation
/// scenario sets (`scenario_set`, seeds `s · 1 000 003 + i`) stay in the lower half for any set
/// seed below 9 · 10¹², so no evaluation ever replays a training scenario.
fn training_episode_seed(seed: u64, updates: u64) -> u64 {
    TRAINING_SEEDS | seed.wrapping_mul(7_919).wrapping_add(updates * 1_000)
}
