//! `fairgrasp train`: the PPO trainer (burn), built with the `train` feature. Without it the
//! command says how to build a fairgrasp that trains; every other command works without burn.

use std::path::PathBuf;

use clap::Args;

#[derive(Args, Debug)]
pub struct TrainArgs {
    /// Training config (TOML); see assets/policies/*/config.toml for complete examples.
    #[arg(long, value_name = "FILE")]
    config: PathBuf,
    /// Run folder (config.toml, metrics.csv, checkpoints/, eval.json). Default: runs/<config name>.
    #[arg(long, value_name = "DIR")]
    run_dir: Option<PathBuf>,
    /// Continue the run in --run-dir from its latest checkpoint.
    #[arg(long)]
    resume: bool,
    /// With --resume: continue even though the config differs from the run's config.toml
    /// (the differences are listed without it). The new values are written to config.toml and
    /// recorded in config_changes.log. total_timesteps, max_wall_time_s and threads may change
    /// without it (with anneal_lr the learning-rate schedule then stretches to the new
    /// total_timesteps); the network's shape ([model] hidden) and [agent] never can.
    #[arg(long, requires = "resume")]
    accept_config_changes: bool,
    /// Start over in a --run-dir that holds a run (or a damaged one): the old run is moved
    /// aside to DIR.replaced-N, never deleted. A folder that is not a run's is refused even so.
    #[arg(long, conflicts_with = "resume")]
    force: bool,
    /// Override the config's seed, 0–9007199254740991 (2⁵³ − 1) (a --resume without it keeps the run's seed).
    #[arg(long, value_parser = crate::cli::args::seed)]
    seed: Option<u64>,
    /// Override the config's total_timesteps, 1–10000000000.
    #[arg(long, value_parser = |t: &str| crate::cli::args::whole_number_in(t, 1..=10_000_000_000))]
    timesteps: Option<u64>,
    /// Override the config's max_wall_time_s: stop after this many seconds of this invocation.
    #[arg(long, value_name = "SECONDS", value_parser = crate::cli::args::positive_seconds)]
    max_wall_time: Option<f64>,
}

/// Without the `train` feature: the exact command that builds a fairgrasp that trains.
#[cfg(not(feature = "train"))]
pub fn run_train(_: &TrainArgs) -> anyhow::Result<std::process::ExitCode> {
    anyhow::bail!(
        "this fairgrasp was built without training (PPO in burn is a large build that compare, \
         eval and replay do not need). Build one that trains and run it the same way:\n  \
         cargo run --release --features train -- train …\n  \
         (or `cargo install --path . --features train`)"
    )
}

#[cfg(feature = "train")]
pub use trainer::run_train;

#[cfg(feature = "train")]
mod trainer {
    use std::path::Path;
    use std::process::ExitCode;
    use std::time::{Duration, Instant};

    use fairgrasp_rl::run::train::{Progress, TrainConfig, train_with};

    use super::TrainArgs;
    use crate::cli::baseline::print_report;

    /// Seconds between two of `train`'s progress lines (the first update and evaluations always
    /// print).
    const TRAIN_LINE_EVERY: Duration = Duration::from_secs(5);

    /// `1h02m`, `4m05s`, `12s`.
    fn duration_text(seconds: f64) -> String {
        if !seconds.is_finite() {
            return "?".into();
        }
        let s = seconds.max(0.0).round() as u64;
        match (s / 3600, (s / 60) % 60, s % 60) {
            (0, 0, sec) => format!("{sec}s"),
            (0, m, sec) => format!("{m}m{sec:02}s"),
            (h, m, _) => format!("{h}h{m:02}m"),
        }
    }

    pub fn run_train(a: &TrainArgs) -> anyhow::Result<ExitCode> {
        let run_dir = a.run_dir.clone().unwrap_or_else(|| {
            let stem = a
                .config
                .file_stem()
                .map_or("run".into(), |s| s.to_string_lossy().into_owned());
            Path::new("runs").join(stem)
        });
        let mut config =
            TrainConfig::from_toml_file_in(&a.config, a.resume.then_some(run_dir.as_path()))?;
        for old in fairgrasp_policy::recipe::read::old_preset_names_in(&a.config) {
            if let Some(note) = fairgrasp_env::config::presets::rename_note(&old) {
                eprintln!("note: {}: {note}", a.config.display());
            }
        }
        if let Some(s) = a.seed {
            config.seed = s;
        }
        if let Some(t) = a.timesteps {
            config.total_timesteps = t;
        }
        if let Some(t) = a.max_wall_time {
            config.max_wall_time_s = Some(t);
        }
        if a.resume && a.seed.is_none() {
            config.seed = fairgrasp_rl::run::resume::run_seed(&run_dir, config.seed)?;
        }
        if a.resume
            && fairgrasp_rl::run::folder::inspect(&run_dir)
                == fairgrasp_rl::run::folder::FolderState::Unstarted
        {
            eprintln!(
                "note: {} holds no checkpoint yet (killed before its first one?): starting it fresh",
                run_dir.display()
            );
        }
        let options = fairgrasp_rl::run::resume::ResumeOptions {
            resume: a.resume,
            accept_config_changes: a.accept_config_changes,
            force: a.force,
        };
        let mut lines = TrainLines::new();
        let report = train_with(&config, &run_dir, options, &mut |p| {
            if let Some(line) = lines.line(&p) {
                eprintln!("{line}");
            }
        })?;
        println!("run folder {}", run_dir.display());
        print_report(
            "trained agent",
            &config.preset,
            config.arm,
            1_000_000,
            &report,
        );
        Ok(ExitCode::SUCCESS)
    }

    /// `train`'s progress: one line per call of [`TrainLines::line`] that is due.
    pub struct TrainLines {
        last: Option<Instant>,
        /// Smoothed environment steps per second.
        speed: Option<f64>,
        updates: u64,
    }

    impl TrainLines {
        pub fn new() -> Self {
            TrainLines {
                last: None,
                speed: None,
                updates: 0,
            }
        }

        /// The line for this update if one is due: the first update, an evaluation, the last
        /// update, or [`TRAIN_LINE_EVERY`] since the previous line.
        pub fn line(&mut self, p: &Progress) -> Option<String> {
            self.updates += 1;
            let speed = match self.speed {
                Some(s) => 0.8 * s + 0.2 * p.steps_per_second,
                None => p.steps_per_second,
            };
            self.speed = Some(speed);
            let done = p.timesteps >= p.total;
            let due = self.last.is_none_or(|t| t.elapsed() >= TRAIN_LINE_EVERY);
            if !(due || done || p.eval.is_some()) {
                return None;
            }
            self.last = Some(Instant::now());
            let n = p.stats.episodes.len();
            let success = if n == 0 {
                "–".to_string()
            } else {
                let s = p.stats.episodes.iter().filter(|e| e.success).count();
                format!("{:.0}%", 100.0 * s as f64 / n as f64)
            };
            let eval = p
                .eval
                .map_or(String::new(), |e| format!(" · eval {:.0}%", 100.0 * e));
            let left = p.total.saturating_sub(p.timesteps) as f64 / speed.max(1e-9);
            Some(format!(
                "train: {}/{} steps ({:.0}%) · stage {} · success {success} ({n} episodes){eval} · {:.0} steps/s · {} left",
                p.timesteps,
                p.total,
                100.0 * p.timesteps as f64 / p.total.max(1) as f64,
                p.stage,
                speed,
                duration_text(left),
            ))
        }
    }
}
