//! `fairgrasp bench soak`: every preset's env stepped with seeded random actions for a long
//! time (`fairgrasp_bench::soak`), presets spread over threads; the table counts anything
//! non-finite, physics faults and env errors (any of them: exit 1) and shows resident memory
//! after the first 10 % and at the end, to compare by eye.

use std::process::ExitCode;
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::Context;
use clap::Args;
use fairgrasp_bench::soak::{SoakReport, ZeroActions, soak};
use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets::{self, PRESETS};
use fairgrasp_env::episode::Policy;
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

#[derive(Args, Debug)]
pub struct SoakArgs {
    /// Env steps per preset, 1–1000000000.
    #[arg(long, default_value_t = 1_000_000, value_parser = |t: &str| super::args::whole_number_in(t, 1..=1_000_000_000))]
    steps: u64,
    /// Presets to soak (default: every shipped preset).
    #[arg(long = "preset", value_name = "NAME", value_parser = super::args::preset)]
    presets: Vec<String>,
    /// Seed of the random actions and the scenarios, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    /// Where actions come from: `script` (the scripted grasp plus uniform noise of ±--noise:
    /// grasps, lifts, drops and pushes, so contacts are exercised) or `random` (uniform in
    /// [−1, 1]: the arm mostly swings in free space).
    #[arg(long, value_enum, default_value = "script")]
    actions: SoakActions,
    /// Noise added to each scripted action component (0–1).
    #[arg(long, default_value_t = 0.3, value_parser = noise_level)]
    noise: f64,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: fairgrasp_types::ArmSimulation,
    /// Threads (presets run side by side, one env each), 1–256.
    #[arg(long, default_value_t = 2, value_parser = super::args::thread_count)]
    threads: usize,
    /// Print the reports as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum SoakActions {
    Script,
    Random,
}

fn noise_level(text: &str) -> Result<f64, String> {
    match super::args::finite_number(text)? {
        v if (0.0..=1.0).contains(&v) => Ok(v),
        v => Err(format!("{v}: must be in [0, 1]")),
    }
}

pub fn run(a: &SoakArgs) -> anyhow::Result<ExitCode> {
    let names: Vec<String> = if a.presets.is_empty() {
        PRESETS.iter().map(|(n, _, _)| n.to_string()).collect()
    } else {
        a.presets.clone()
    };
    let configs = names
        .iter()
        .map(|n| {
            let mut c = presets::load(n).with_context(|| format!("preset {n}"))?;
            c.arm.model = a.arm;
            Ok(c)
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let results = soak_presets(a, &configs)?;
    let mut rows = Vec::new();
    let mut clean = true;
    for (name, r) in names.iter().zip(results) {
        let (r, secs) = r.context("a soak thread stopped early")??;
        clean &= r.is_clean();
        rows.push((name.clone(), r, secs));
    }
    if a.json {
        let v: Vec<_> = rows
            .iter()
            .map(|(n, r, s)| serde_json::json!({"preset": n, "seconds": s, "report": r}))
            .collect();
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        print_table(&rows);
    }
    Ok(if clean {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// One preset's soak: its report and the wall time it took \[s\].
type SoakResult = anyhow::Result<(SoakReport, f64)>;

/// Soaks every config, presets side by side on up to --threads threads, under one progress bar
/// of env steps. The results are in `configs`' order; `None` where no thread got to the preset
/// (a thread stopped early).
fn soak_presets(a: &SoakArgs, configs: &[EnvConfig]) -> anyhow::Result<Vec<Option<SoakResult>>> {
    let done = AtomicU64::new(0);
    let bar = indicatif::ProgressBar::new(a.steps * configs.len() as u64);
    bar.set_style(indicatif::ProgressStyle::with_template(
        "{bar:30} {pos}/{len} env steps {per_sec} eta {eta}",
    )?);
    let next = AtomicU64::new(0);
    let mut results: Vec<Option<SoakResult>> = (0..configs.len()).map(|_| None).collect();
    let slots: Vec<std::sync::Mutex<&mut Option<_>>> =
        results.iter_mut().map(std::sync::Mutex::new).collect();
    std::thread::scope(|s| {
        for _ in 0..a.threads.min(configs.len()) {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed) as usize;
                    let Some(config) = configs.get(i) else { break };
                    let r = soak_preset(a, config, &done, &bar);
                    **slots[i].lock().expect("no thread panicked holding it") = Some(r);
                }
            });
        }
    });
    drop(slots);
    bar.finish_and_clear();
    Ok(results)
}

/// Soaks one preset for --steps env steps with --actions (the script plus ±--noise, or uniform
/// random actions), adding the steps done to `done` and the progress bar as it goes.
fn soak_preset(
    a: &SoakArgs,
    config: &EnvConfig,
    done: &AtomicU64,
    bar: &indicatif::ProgressBar,
) -> SoakResult {
    let start = std::time::Instant::now();
    let mut last = 0;
    let (mut policy, noise): (Box<dyn Policy>, f64) = match a.actions {
        SoakActions::Script => (
            Box::new(ScriptedGrasp::new(config, BaselineConfig::default())),
            a.noise,
        ),
        SoakActions::Random => (Box::new(ZeroActions), 1.0),
    };
    let r = soak(config, policy.as_mut(), noise, a.steps, a.seed, &mut |t| {
        done.fetch_add(t - last, Ordering::Relaxed);
        last = t;
        bar.set_position(done.load(Ordering::Relaxed));
    });
    let r = r.map(|r| (r, start.elapsed().as_secs_f64()));
    r.map_err(anyhow::Error::from)
}

/// The reports as a table, one row per preset (name, report, seconds), with each preset's first
/// env error under its row.
fn print_table(rows: &[(String, SoakReport, f64)]) {
    println!(
        "{:<16} {:>10} {:>9} {:>8} {:>7} {:>7} {:>7} {:>6} {:>10} {:>10}",
        "preset",
        "steps",
        "physics",
        "episodes",
        "NaN obs",
        "NaN rew",
        "faults",
        "errors",
        "RSS 10% MiB",
        "RSS end MiB"
    );
    for (n, r, _) in rows {
        println!(
            "{:<16} {:>10} {:>9} {:>8} {:>7} {:>7} {:>7} {:>6} {:>10.1} {:>10.1}",
            n,
            r.steps,
            r.physics_steps,
            r.episodes,
            r.non_finite_observations,
            r.non_finite_rewards,
            r.physics_faults,
            r.env_errors,
            r.rss_after_warmup_kib as f64 / 1024.0,
            r.rss_end_kib as f64 / 1024.0
        );
        if let Some(e) = &r.first_error {
            println!("  first error: {e}");
        }
    }
    println!("(resident memory is the process's: presets soaked side by side share it)");
}
