//! `fairgrasp replay`: one scenario run by one or more policies, recorded, and written as the
//! interactive 3D replay (one self-contained HTML file; see `fairgrasp_report::replay3d`).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::Args;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_eval::compare::methods::Method;
use fairgrasp_eval::compare::record::record_episodes;
use fairgrasp_eval::compare::{LearnedPolicy, scripts_for};
use fairgrasp_report::replay3d::{self, ReplayEpisode};
use fairgrasp_types::ArmSimulation;

use super::baseline::preset_config;

#[derive(Args, Debug)]
pub struct ReplayArgs {
    /// What acts: a script (open_loop, closed_loop, oracle, calibrated), or a policy as every
    /// command takes one: a shipped policy by name (residual_hard, pure_full, …), a policy folder
    /// (assets/policies/pure_full), a checkpoint folder (…/checkpoint) or a run folder (its
    /// checkpoints/best). Repeat the flag to run several on the same scenario (shown side by side
    /// in the page).
    #[arg(long = "policy", value_name = "P", required = true)]
    policies: Vec<String>,
    /// Preset name or a .toml env config.
    #[arg(long, default_value = "seed")]
    preset: String,
    /// Index of the scenario in the preset's seeded set (the same scenario `fairgrasp compare
    /// --seed S` calls episode N), 0–999999.
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = super::args::scenario_index)]
    episode: usize,
    /// Seed of the scenario set, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmSimulation,
    /// The HTML file to write. An existing file is replaced only if it is a fairgrasp replay.
    #[arg(long, value_name = "FILE.html", default_value = "replay.html")]
    out: PathBuf,
}

pub fn run(a: &ReplayArgs) -> anyhow::Result<ExitCode> {
    if a.out.exists() && !replay3d::is_replay_file(&a.out) {
        bail!(
            "--out {}: the file exists and is not a fairgrasp replay; choose another name (it is \
             never replaced)",
            a.out.display()
        );
    }
    let config =
        preset_config(&a.preset, a.arm).with_context(|| format!("preset `{}`", a.preset))?;
    let scenarios = scenario_set(&config, a.seed, a.episode + 1)
        .with_context(|| format!("preset `{}`: drawing scenario {}", a.preset, a.episode))?;
    let mut learned: Vec<LearnedPolicy> = Vec::new();
    let mut methods = Vec::new();
    let mut names = Vec::new();
    for p in &a.policies {
        let method = Method::resolve(p)?;
        method.check_task(&config)?;
        names.push(method.name());
        match method {
            Method::Script(i) => methods.push(i),
            Method::Learned(l) => {
                methods.push(scripts_for(&config).len() + learned.len());
                learned.push(*l);
            }
        }
    }
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let recordings = record_episodes(
        &config,
        &scenarios,
        &[a.episode],
        &methods,
        &learned,
        threads,
    )?;
    let episodes: Vec<ReplayEpisode<'_>> = recordings
        .iter()
        .zip(&names)
        .map(|(r, name)| ReplayEpisode {
            method: name.clone(),
            preset: a.preset.clone(),
            episode: a.episode,
            outcome: Some(r.outcome),
            trajectory: &r.trajectory,
        })
        .collect();
    let title = format!(
        "fairgrasp replay: {} on {} #{}",
        names.join(" vs "),
        a.preset,
        a.episode
    );
    replay3d::write_replay(&a.out, &title, &episodes)?;
    for (name, r) in names.iter().zip(&recordings) {
        println!(
            "{name}: {} in {} steps",
            r.outcome,
            r.trajectory.rows.len().saturating_sub(1)
        );
    }
    let with = if episodes.len() > 1 { "&with=1" } else { "" };
    println!(
        "Written {} ({} KB): open it in a browser, e.g. {}#episode=0&t=0{with}",
        a.out.display(),
        std::fs::metadata(&a.out).map_or(0, |m| m.len() / 1024),
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
