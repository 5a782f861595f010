//! `fairgrasp tune`: a hand-written control's parameters tuned by CMA-ES on training scenarios
//! (`fairgrasp_evaluate::tune`), with a budget of env steps; every trial in `trials.csv`, the
//! best as a preset fragment (`tuned.toml`) that `baseline --tuned` and `compare --tuned` read.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};

use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_evaluate::tune::fragment::env_steps_text;
use fairgrasp_evaluate::tune::spec::{
    DEFAULT_FINALISTS, DEFAULT_STALL_GENERATIONS, DEFAULT_VALIDATION_EPISODES, MAX_BUDGET,
    MAX_EPISODES_PER_TRIAL, MAX_FINALISTS,
};
use fairgrasp_evaluate::tune::{
    TuneError, TuneEvent, TuneOutcome, TuneSpec, Validation, folder, run_tune,
};
use fairgrasp_types::ArmSimulation;

use crate::cli::UsageError;
use crate::cli::baseline::preset_config;

/// The place residual's training budget \[env steps\]: what a control tuned against it gets.
const DEFAULT_BUDGET: u64 = 3_000_000;

#[derive(Args, Debug)]
#[command(after_help = "Examples:
  fairgrasp tune --preset place_cell --control force_search --out tuned/place_cell_search
  fairgrasp tune --preset place_cell --control force_search --param pitch=0.001:0.004 --param speed --budget 500000 --out t
  fairgrasp tune --preset heavy_slippery --control tuned_grip --out tuned/grip

Before it writes tuned.toml, the best trials (--finalists) run again on validation scenarios
of their own (--validation-seed, --validation-episodes) and the best there is chosen; the
budget holds both. Ctrl-C stops it; the same command again resumes it, trial for trial. The
tuned setting is tuned.toml in the folder (an edited tuned.toml is kept, the new one written
beside it as tuned.new.toml): `fairgrasp baseline --preset P --script C --tuned FOLDER/tuned.toml`
runs it (on a held-out seed, e.g. --seed 7), `fairgrasp compare --tuned …` compares it.")]
pub struct TuneArgs {
    /// The preset (or .toml file) whose training scenarios the control is tuned on.
    #[arg(long, value_parser = crate::cli::args::preset)]
    preset: String,
    /// The control, by its command-line name (as `baseline --script` takes it): on a place
    /// preset force_search, closed_loop_force_search, square_search or switch_search; on a
    /// lift preset tuned_grip.
    #[arg(long)]
    control: String,
    /// A parameter to tune, with an optional range `NAME=LOW:HIGH` (repeat it; without any,
    /// every parameter of the control in its default range). `--list` shows them.
    #[arg(long = "param", value_name = "NAME[=LOW:HIGH]", value_parser = param_range)]
    params: Vec<(String, Option<[f64; 2]>)>,
    /// Env steps to spend, 1–1000000000 (the trial running when they are spent finishes).
    #[arg(long, default_value_t = DEFAULT_BUDGET, value_parser = budget)]
    budget: u64,
    /// Episodes per trial, 1–100000: the same training scenarios for every trial.
    #[arg(long, default_value_t = 150, value_parser = episodes_per_trial)]
    episodes: usize,
    /// Seed of the training scenarios, 0–9007199254740991 (2⁵³ − 1): never the seed results are
    /// reported on (7).
    #[arg(long, default_value_t = 11, value_parser = crate::cli::args::seed)]
    seed: u64,
    /// The optimiser's seed, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = crate::cli::args::seed)]
    optimiser_seed: u64,
    /// The best trials re-evaluated on the validation's scenarios before one is chosen,
    /// 1–100 (distinct settings, by their score).
    #[arg(long, default_value_t = DEFAULT_FINALISTS, value_parser = finalists)]
    finalists: usize,
    /// Seed of the validation's scenarios, 0–9007199254740991 (2⁵³ − 1): training scenarios of
    /// their own, neither --seed nor 7 [default: 12, or 13 when --seed is 12]
    #[arg(long, value_parser = crate::cli::args::seed)]
    validation_seed: Option<u64>,
    /// Validation episodes per finalist, 1–100000.
    #[arg(long, default_value_t = DEFAULT_VALIDATION_EPISODES, value_parser = episodes_per_trial)]
    validation_episodes: usize,
    /// Generations without a better trial after which the search restarts around the best
    /// with half the spread, 0–1000 (0: never).
    #[arg(long, default_value_t = DEFAULT_STALL_GENERATIONS, value_parser = stall)]
    stall: usize,
    /// The tuning's folder: new or empty, or one of this same tuning to resume.
    #[arg(long, value_name = "DIR", required_unless_present = "list")]
    out: Option<PathBuf>,
    /// Worker threads, 1–256 (default: all cores).
    #[arg(long, value_parser = crate::cli::args::thread_count)]
    threads: Option<usize>,
    /// List the control's parameters (name, unit, what it accepts, default range) and stop.
    #[arg(long)]
    list: bool,
}

/// A budget of env steps, 1–[`MAX_BUDGET`] (clap value parser).
fn budget(text: &str) -> Result<u64, String> {
    crate::cli::args::whole_number_in(text, 1..=MAX_BUDGET)
}

/// Episodes per trial, 1–[`MAX_EPISODES_PER_TRIAL`] (clap value parser).
fn episodes_per_trial(text: &str) -> Result<usize, String> {
    crate::cli::args::whole_number_in(text, 1..=MAX_EPISODES_PER_TRIAL as u64).map(|n| n as usize)
}

/// Finalists, 1–[`MAX_FINALISTS`] (clap value parser).
fn finalists(text: &str) -> Result<usize, String> {
    crate::cli::args::whole_number_in(text, 1..=MAX_FINALISTS as u64).map(|n| n as usize)
}

/// Generations of a stall, 0–1000 (clap value parser).
fn stall(text: &str) -> Result<usize, String> {
    crate::cli::args::whole_number_in(text, 0..=1000).map(|n| n as usize)
}

/// `NAME` or `NAME=LOW:HIGH`.
fn param_range(text: &str) -> Result<(String, Option<[f64; 2]>), String> {
    let Some((name, range)) = text.split_once('=') else {
        return Ok((text.to_string(), None));
    };
    let (lo, hi) = range
        .split_once(':')
        .ok_or_else(|| format!("`{text}`: a range is NAME=LOW:HIGH"))?;
    let num = |s: &str| {
        s.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("`{text}`: `{s}` is not a finite number"))
    };
    Ok((name.to_string(), Some([num(lo)?, num(hi)?])))
}

/// The preset's config the tuning runs on: a resumed tuning of a preset file runs on the preset
/// its folder recorded (a note says when the file here differs), anything else reads the preset.
fn tuning_preset(a: &TuneArgs) -> anyhow::Result<EnvConfig> {
    if let Some(dir) = a.out.as_deref().filter(|_| !a.list)
        && let Some((config, note)) = folder::recorded_preset_file(dir, &a.preset)?
    {
        if let Some(note) = note {
            eprintln!("note: {note}");
        }
        return Ok(config);
    }
    preset_config(&a.preset, ArmSimulation::Servo)
}

pub fn run(a: &TuneArgs) -> anyhow::Result<ExitCode> {
    let config = tuning_preset(a)?;
    if a.list {
        return list(&config, &a.control);
    }
    let spec = tune_spec(a, config)?;
    let dir = a.out.clone().expect("clap requires --out without --list");
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    eprintln!(
        "tuning `{}` on `{}`: {} over {}, {} episodes per trial of seed {}; the best {} re-evaluated on {} episodes of seed {}; a budget of {} for both ({})",
        spec.control.cli,
        spec.preset,
        spec.objective.describe(),
        spec.names().join(", "),
        spec.episodes,
        spec.scenario_seed,
        spec.validation.finalists,
        spec.validation.episodes,
        spec.validation.seed,
        env_steps(spec.budget),
        dir.display()
    );
    let episodes = AtomicUsize::new(0);
    let live = std::io::stderr().is_terminal();
    let outcome = run_tune(&spec, &dir, threads, &|e| {
        report(&e, &episodes, live, spec.episodes)
    })?;
    print_outcome(&spec, &outcome, &dir);
    Ok(ExitCode::SUCCESS)
}

/// The tuning `a` asks for on `config`, its validation and stall rule included. A request that
/// cannot run is a usage error.
fn tune_spec(a: &TuneArgs, config: EnvConfig) -> anyhow::Result<TuneSpec> {
    // A request that cannot run (a control or parameter the preset has not, a range outside
    // what it accepts) is a usage error: exit code 2, as clap's own.
    TuneSpec::new(
        &a.preset,
        config,
        &a.control,
        &a.params,
        a.seed,
        a.episodes,
        a.budget,
        a.optimiser_seed,
    )
    .and_then(|spec| {
        let defaults = Validation::default_for(a.seed);
        spec.with_validation(Validation {
            seed: a.validation_seed.unwrap_or(defaults.seed),
            episodes: a.validation_episodes,
            finalists: a.finalists,
        })
    })
    .map(|spec| spec.with_stall_generations(a.stall))
    .map_err(|e| match e {
        TuneError::Request(m) => anyhow::Error::new(UsageError(m)),
        other => other.into(),
    })
}

/// What the tuning chose, its env steps and where its files are.
fn print_outcome(spec: &TuneSpec, outcome: &TuneOutcome, dir: &Path) {
    let best = &outcome.trials[outcome.best];
    let counted = |t: &fairgrasp_evaluate::tune::trials::Trial| match spec.objective {
        fairgrasp_evaluate::tune::Objective::SuccessWithinTakt => t.within_takt,
        fairgrasp_evaluate::tune::Objective::Success => t.successes,
    };
    let validation = outcome
        .finalists
        .iter()
        .find(|f| f.trial.index == best.index)
        .map_or(String::new(), |f| {
            format!(
                "; on validation {:.1} % ({} of {} episodes of seed {})",
                100.0 * f.validation.objective,
                counted(&f.validation),
                f.validation.episodes,
                spec.validation.seed
            )
        });
    println!(
        "chosen: trial {} of {}, {} {:.1} % ({} of {} episodes{}){validation}",
        best.index,
        outcome.trials.len(),
        spec.objective.describe(),
        100.0 * best.objective,
        counted(best),
        best.episodes,
        best.mean_cycle_time_s
            .map_or(String::new(), |c| format!(", mean cycle {c:.1} s")),
    );
    println!(
        "env steps: {} on the trials + {} on the validation = {} (budget {})",
        env_steps(outcome.search_env_steps),
        env_steps(outcome.validation_env_steps),
        env_steps(outcome.note.env_steps),
        env_steps(spec.budget)
    );
    for (name, v) in &best.values {
        println!("  {name:<14} {v}");
    }
    if let Some(kept) = &outcome.fragment.kept_edited {
        eprintln!(
            "note: {} was edited since `tune` wrote it and is kept; the new setting is in {} (move it over {} to use it there)",
            kept.display(),
            outcome.fragment.path.display(),
            kept.display()
        );
    }
    println!(
        "trials: {}; finalists: {}; the setting: {}",
        dir.join("trials.csv").display(),
        dir.join("finalists.csv").display(),
        outcome.fragment.path.display()
    );
}

/// One progress line per trial on stderr (and a running count of episodes on a terminal).
fn report(e: &TuneEvent<'_>, episodes: &AtomicUsize, live: bool, per_trial: usize) {
    match e {
        TuneEvent::Resumed { trials, env_steps } => eprintln!(
            "resuming: {trials} trials ({}) already in the folder",
            self::env_steps(*env_steps)
        ),
        TuneEvent::TrialStart { .. } => episodes.store(0, Ordering::Relaxed),
        TuneEvent::Episode => {
            let n = episodes.fetch_add(1, Ordering::Relaxed) + 1;
            if live {
                eprint!("\r  {n}/{per_trial} episodes");
            }
        }
        TuneEvent::TrialDone {
            trial,
            best,
            spent,
            budget,
        } => {
            if live {
                eprint!("\r");
            }
            eprintln!(
                "trial {:>3} (gen {:>2}): {:5.1} %   best {:5.1} % (trial {})   {} of {}",
                trial.index,
                trial.generation,
                100.0 * trial.objective,
                100.0 * best.objective,
                best.index,
                env_steps(*spent),
                env_steps(*budget)
            );
        }
        TuneEvent::Restart {
            generation,
            sigma,
            stalled,
        } => eprintln!(
            "restart at generation {generation} around the best trial, spread {sigma:.4} ({})",
            match stalled {
                Some(n) => format!("nothing better for {n} generations"),
                None => "the optimiser converged".to_string(),
            }
        ),
        TuneEvent::FinalistStart { rank, of, trial } => {
            episodes.store(0, Ordering::Relaxed);
            eprintln!("validation: finalist {} of {of} (trial {trial})", rank + 1);
        }
        TuneEvent::FinalistDone { finalist } => {
            if live {
                eprint!("\r");
            }
            eprintln!(
                "  trial {:>3}: {:5.1} % on its trial, {:5.1} % on validation",
                finalist.trial.index,
                100.0 * finalist.trial.objective,
                100.0 * finalist.validation.objective
            );
        }
    }
}

/// A count of env steps as people read it: `1500 env steps`, `3.00 M env steps`.
fn env_steps(n: u64) -> String {
    env_steps_text(n)
}

/// Prints the control's parameters.
fn list(config: &EnvConfig, name: &str) -> anyhow::Result<ExitCode> {
    let task = config.task.kind;
    let Some(c) = fairgrasp_planner::controls::control(task, name) else {
        return Err(UsageError(format!(
            "--control {name}: not a control of this preset's task; choose one of {}",
            fairgrasp_planner::controls::control_names(task).join(", ")
        ))
        .into());
    };
    let now = (c.values)(config);
    println!("{} ({}): {} parameters", c.cli, c.report, c.params.len());
    for p in c.params {
        println!(
            "  {:<14} {:<11} accepts [{}, {}], searched [{}, {}] ({:?}), now {}: {}",
            p.name,
            p.unit,
            p.accepts[0],
            p.accepts[1],
            p.range[0],
            p.range[1],
            p.scale,
            now.get(p.name).copied().unwrap_or(f64::NAN),
            p.doc
        );
    }
    Ok(ExitCode::SUCCESS)
}
