//! `fairgrasp compare`: the baseline and learned policies on identical seeded scenario sets,
//! with the table, compare.csv/json, charts, replays and the notebook in one folder.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use fairgrasp_env::TaskKind;
use fairgrasp_env::config::presets;
use fairgrasp_evaluate::compare::{
    ComparePreset, CompareSpec, DEFAULT_REPLAY_EPISODES, LearnedPolicy, default_threads,
    run_comparison, run_folder_of,
};
use fairgrasp_evaluate::tune::fragment;
use fairgrasp_policy::recipe::{EnvFor, Recipe};
use fairgrasp_policy::shipped;
use fairgrasp_report::comparison_folder::write_comparison_folder;
use fairgrasp_report::comparison_table;
use fairgrasp_report::{Existing, StagedFolder};
use fairgrasp_types::ArmSimulation;

use super::baseline::preset_config;

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Presets (or .toml env configs) to compare on; repeat the flag for several.
    /// Default: sector, full, hard, the four scenario families (miscalibrated,
    /// miscalibrated_b, nudged, wrist_camera) and the contact family (heavy_slippery).
    #[arg(long = "preset", value_name = "NAME", value_parser = super::args::preset)]
    presets: Vec<String>,
    /// Episodes (scenarios) per preset, 1–1000000; every method gets the same ones.
    #[arg(long, default_value_t = 100, value_parser = super::args::episode_count)]
    episodes: u32,
    /// Learned policies; repeat for several: a shipped policy's name (residual_nudged, …), a
    /// policy folder (assets/policies/NAME), a checkpoint folder or a run folder (its
    /// checkpoints/best), or `all` for every shipped policy (the specialists too; all but the
    /// pitfall exhibit pure_hard). Default: the shipped generalist residual
    /// (residual_generalist) and pure PPO (pure_full) where the presets' task is the one they
    /// were trained on (lift); on place presets none unless named.
    /// Every comparison also runs the task's scripts: for lift the open-loop baseline, the
    /// closed-loop script, the oracle, the open-loop script after a simulated camera
    /// calibration and the open-loop script with the grip tuned for the preset; for place the
    /// place script, the tuned force-guided search, and both in closed loop.
    #[arg(long = "policy", value_name = "NAME|DIR|all")]
    policies: Vec<String>,
    /// A tuned control's setting (`fairgrasp tune`'s tuned.toml), read into the preset it was
    /// tuned on, which must be one of --preset; repeat for several. Presets that carry their
    /// tuned settings (place_cell) need none.
    #[arg(long = "tuned", value_name = "FILE")]
    tuned: Vec<PathBuf>,
    /// Seed of the scenario sets, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmSimulation,
    /// Worker threads, 1–256 (default: one per core).
    #[arg(long, value_parser = super::args::thread_count)]
    threads: Option<usize>,
    /// Output folder: compare.csv, compare.json, charts, replays, report.md, report.ipynb. It
    /// must be new or empty, or (with --force) one an earlier `fairgrasp compare` or `report`
    /// wrote. It is checked, and DIR.partial-<pid> created next to it, before any episode
    /// runs; everything is written there and moved into place only when complete, so an error
    /// or interrupt never leaves old and new files mixed in DIR.
    #[arg(long, value_name = "DIR", default_value = "report")]
    out: PathBuf,
    /// Replace --out if an earlier `fairgrasp compare` or `fairgrasp report` wrote it (it holds
    /// a .fairgrasp-report file) and no file in it was edited or added since (an edited
    /// report.md, your notes, charts drawn into it later with `plot`: these are named and
    /// nothing is replaced). A folder fairgrasp did not write is never replaced.
    #[arg(long)]
    force: bool,
    /// Scenario index (on the last preset) recorded for the episode charts and replays,
    /// 0–999999 (and below --episodes). Default: the first one where the first two methods end
    /// differently, else 0.
    #[arg(long, value_name = "K", value_parser = super::args::scenario_index)]
    episode: Option<usize>,
    /// Scenarios of every preset recorded for every method for the 3D replay (replay.html):
    /// the first N of each set, and the first where the baseline and the first learned policy
    /// end differently (on the last preset, the --episode one), 0–1000000. 0: no replay.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_REPLAY_EPISODES,
          value_parser = super::args::scenario_count)]
    replay_episodes: usize,
    /// Print compare.json on stdout instead of the table.
    #[arg(long)]
    json: bool,
    /// Print every row (failures, collisions, steps), every paired test and every file written,
    /// not only the pivot table and the tests against the baseline and the best script.
    #[arg(long, short = 'v')]
    verbose: bool,
}

/// The checkpoint folders `--policy` names; when none is given, the shipped policies compared
/// by default ([`shipped::default_compare_policies`]) that were trained on `task`, the presets'
/// task (none when `task` is `None`: the first preset did not load). The shipped policies are
/// all the lift task's, so a place comparison runs its scripts alone unless policies are named.
fn policy_folders(names: &[String], task: Option<TaskKind>) -> anyhow::Result<Vec<PathBuf>> {
    if names.is_empty() {
        let Some(task) = task else {
            return Ok(Vec::new());
        };
        let mut dirs = Vec::new();
        for dir in shipped::default_compare_policies()? {
            if trained_task(&dir)? == task {
                dirs.push(dir);
            }
        }
        return Ok(dirs);
    }
    let mut dirs = Vec::new();
    for name in names {
        if name == "all" {
            dirs.extend(shipped::all_compare_policies()?);
        } else {
            dirs.push(
                shipped::checkpoint_folder(name).map_err(|e| anyhow::anyhow!("--policy: {e}"))?,
            );
        }
    }
    Ok(dirs)
}

/// The task a learned policy was trained on: that of its recipe's first preset (the run's
/// `config.toml`, which a shipped policy's folder holds beside its checkpoint folder).
fn trained_task(checkpoint: &Path) -> anyhow::Result<TaskKind> {
    let run = run_folder_of(checkpoint).with_context(|| {
        format!(
            "{}: no run folder (metrics.csv) holds this checkpoint, so its training recipe is \
             unknown",
            checkpoint.display()
        )
    })?;
    let path = run.join("config.toml");
    let what = || format!("{}: the policy's training recipe", path.display());
    let recipe = Recipe::from_toml_file(&path).with_context(what)?;
    let envs = recipe
        .env_configs(EnvFor::Evaluation)
        .map_err(anyhow::Error::msg)
        .with_context(what)?;
    let first = envs.first().with_context(what)?;
    Ok(first.task.kind)
}

/// Reads each tuned fragment into the preset it was tuned on (one of `presets`, checked by its
/// content as read, before any fragment); two fragments of one control for one preset are
/// refused (the second would silently win).
fn apply_tuned(presets: &mut [ComparePreset], fragments: &[PathBuf]) -> anyhow::Result<()> {
    let bases: Vec<_> = presets.iter().map(|p| p.config.clone()).collect();
    let mut claimed: Vec<(usize, &'static str, &PathBuf)> = Vec::new();
    for path in fragments {
        let mut errors = Vec::new();
        let mut applied = false;
        for (i, p) in presets.iter_mut().enumerate() {
            let mut config = p.config.clone();
            match fragment::apply_to(&mut config, &p.name, &bases[i], path) {
                Ok(control) => {
                    if let Some((_, _, first)) = claimed
                        .iter()
                        .find(|(j, c, _)| *j == i && *c == control.cli)
                    {
                        anyhow::bail!(
                            "--tuned {}: a second fragment of `{}` for preset `{}` (the first is {}): one fragment a control, or the second would silently win",
                            path.display(),
                            control.cli,
                            p.name,
                            first.display()
                        );
                    }
                    claimed.push((i, control.cli, path));
                    p.config = config;
                    applied = true;
                }
                Err(e) => errors.push(e.to_string()),
            }
        }
        if !applied {
            anyhow::bail!(
                "--tuned {}: fits none of the presets compared ({})",
                path.display(),
                errors.join("; ")
            );
        }
    }
    Ok(())
}

pub fn run(a: &CompareArgs) -> anyhow::Result<ExitCode> {
    let names = if a.presets.is_empty() {
        fairgrasp_evaluate::compare::DEFAULT_PRESETS
            .map(String::from)
            .to_vec()
    } else {
        a.presets.clone()
    };
    // A preset that does not load is refused below, naming it.
    let task = presets::load(&names[0]).ok().map(|c| c.task.kind);
    let policy_paths = policy_folders(&a.policies, task)?;
    let mut presets = names
        .iter()
        .map(|p| {
            let config = preset_config(p, a.arm).with_context(|| format!("preset `{p}`"))?;
            Ok(ComparePreset {
                name: p.clone(),
                config,
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    apply_tuned(&mut presets, &a.tuned)?;
    let spec = CompareSpec {
        presets,
        episodes: a.episodes as usize,
        seed: a.seed,
        threads: a.threads.unwrap_or_else(default_threads),
        episode: a.episode,
        replay_episodes: a.replay_episodes,
        command: std::iter::once("fairgrasp".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" "),
    };
    // Refuse a bad request before loading anything.
    spec.check()?;
    let learned = LearnedPolicy::load_all(&policy_paths)
        .context("loading the policy (pass --policy DIR to choose one)")?;
    // The output folder is checked and its staging folder created before the episodes run.
    let staged = StagedFolder::create(&a.out, Existing::from_force(a.force), "fairgrasp compare")?;
    let bars = std::sync::Mutex::new(super::progress::CompareBars::new(
        u64::from(a.episodes),
        a.json,
    ));
    let output = run_comparison(&spec, &learned, &|event| {
        if let Ok(mut b) = bars.lock() {
            b.event(event);
        }
    })?;

    let comparison = &output.comparison;
    let written = write_comparison_folder(staged, comparison, &a.out, spec.threads, |dir| {
        output.save_episodes(dir).map_err(|e| e.to_string())
    })?;
    if a.json {
        println!("{}", comparison.to_json());
    } else if a.verbose {
        print_everything(a, comparison, &written)?;
    } else {
        print_summary(a, comparison, &written)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The default output: the pivot table, the tests against the baseline and the best script,
/// and where the rest is (under 60 lines for the default comparison).
fn print_summary(
    a: &CompareArgs,
    comparison: &fairgrasp_types::Comparison,
    written: &[String],
) -> anyhow::Result<()> {
    print!("{}", comparison_table::pivot_text(comparison));
    let tuning = comparison_table::tuning_text(comparison);
    if !tuning.is_empty() {
        println!("\nHow the controls were set:");
        print!("{tuning}");
    }
    let key = comparison_table::key_paired_text(comparison)?;
    if !key.is_empty() {
        println!(
            "\nPaired tests (McNemar, exact, two-sided; on a task with a takt, of success within \
             it): each learned method vs the baseline and vs the preset's best script (an \
             oracle sees the truth: not a control):"
        );
        print!("{key}");
    }
    println!(
        "\n{} episodes per preset from seed {}, {} arm. Intervals, failures and every other \
         test: {}/report.md, compare.csv (or --verbose).",
        a.episodes,
        a.seed,
        a.arm,
        a.out.display()
    );
    let charts = written
        .iter()
        .filter(|f| f.ends_with(".png") || f.ends_with(".gif"))
        .count();
    println!(
        "Written to {}: report.md, report.ipynb{}, compare.csv, compare.json, {charts} charts \
         and replays, episodes/.",
        a.out.display(),
        if written.iter().any(|f| f == "replay.html") {
            ", replay.html (3D)"
        } else {
            ""
        }
    );
    Ok(())
}

/// `--verbose`: every row, every paired test, every file.
fn print_everything(
    a: &CompareArgs,
    comparison: &fairgrasp_types::Comparison,
    written: &[String],
) -> anyhow::Result<()> {
    print!("{}", comparison_table::pivot_text(comparison));
    println!();
    print!("{}", comparison_table::text_table(comparison));
    let paired = comparison_table::paired_text(comparison)?;
    if !paired.is_empty() {
        println!("\nPaired tests (McNemar, exact, two-sided), learned method vs script:");
        print!("{paired}");
    }
    println!(
        "\n{} episodes per preset from seed {}, {} arm; 95 % Wilson intervals.",
        a.episodes, a.seed, a.arm
    );
    println!("Written to {}:", a.out.display());
    for n in written {
        println!("  {n}");
    }
    Ok(())
}
