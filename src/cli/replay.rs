//! `fairgrasp replay`: one scenario run by one or more policies, recorded, and written as the
//! interactive 3D replay (one self-contained HTML file; see `fairgrasp_report::replay3d`), and/or
//! as JSON (`--json`, [`json`]: what `python -m fairgrasp.rerun` turns into a Rerun `.rrd`).

mod json;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::Args;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_evaluate::compare::methods::{Method, numbered, scripts_by_task};
use fairgrasp_evaluate::compare::record::record_episodes;
use fairgrasp_report::replay3d::{self, ReplayEpisode};
use fairgrasp_types::ArmSimulation;

use super::baseline::preset_config;

#[derive(Args, Debug)]
pub struct ReplayArgs {
    // Its help (`policy_help`) lists each task's scripts from the planner's table.
    #[arg(long = "policy", value_name = "P", required = true, help = policy_help())]
    policies: Vec<String>,
    /// Preset name or a .toml env config.
    #[arg(long, default_value = "sector", value_parser = super::args::preset)]
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
    /// The HTML file to write [default: replay.html, unless --json is given]. An existing file
    /// is replaced only if it is a fairgrasp replay.
    #[arg(long, value_name = "FILE.html")]
    out: Option<PathBuf>,
    /// Also (or, without --out, only) write the recorded episodes as JSON: each method's
    /// trajectory and the contact forces of every step, what `python -m fairgrasp.rerun` turns
    /// into a Rerun .rrd. An existing file is replaced only if it is such a JSON.
    #[arg(long, value_name = "FILE.json")]
    json: Option<PathBuf>,
}

/// `--policy`'s help: what acts, each task's scripts by name (the planner's table of controls,
/// [`scripts_by_task`]) and the learned policies.
fn policy_help() -> String {
    format!(
        "What acts: a script, a control of the preset's task by name ({}), or a policy as every \
         command takes one: a shipped policy by name (residual_hard, pure_full, …), a policy \
         folder (assets/policies/pure_full), a checkpoint folder (…/checkpoint) or a run folder \
         (its checkpoints/best). Repeat the flag to run several on the same scenario (shown side \
         by side in the page).",
        scripts_by_task()
    )
}

pub fn run(a: &ReplayArgs) -> anyhow::Result<ExitCode> {
    let html = match (&a.out, &a.json) {
        (Some(out), _) => Some(out.clone()),
        (None, Some(_)) => None,
        (None, None) => Some(PathBuf::from("replay.html")),
    };
    if let Some(out) = html.as_ref().filter(|o| o.exists())
        && !replay3d::is_replay_file(out)
    {
        bail!(
            "--out {}: the file exists and is not a fairgrasp replay; choose another name (it is \
             never replaced)",
            out.display()
        );
    }
    if let Some(path) = a.json.as_ref().filter(|p| p.exists())
        && !json::is_replay_json(path)
    {
        bail!(
            "--json {}: the file exists and is not a fairgrasp replay JSON; choose another name \
             (it is never replaced)",
            path.display()
        );
    }
    let config =
        preset_config(&a.preset, a.arm).with_context(|| format!("preset `{}`", a.preset))?;
    let scenarios = scenario_set(&config, a.seed, a.episode + 1)
        .with_context(|| format!("preset `{}`: drawing scenario {}", a.preset, a.episode))?;
    let resolved = a
        .policies
        .iter()
        .map(|p| Method::resolve(p, config.task.kind))
        .collect::<Result<Vec<_>, _>>()?;
    let names: Vec<String> = resolved.iter().map(Method::name).collect();
    let (methods, scripts, learned) = numbered(resolved);
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let recordings = record_episodes(
        &config,
        &scenarios,
        &[a.episode],
        &methods,
        &scripts,
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
    for (name, r) in names.iter().zip(&recordings) {
        println!(
            "{name}: {} in {} steps",
            r.outcome,
            r.trajectory.rows.len().saturating_sub(1)
        );
    }
    if let Some(out) = &html {
        write_html(out, a, &names, &episodes)?;
    }
    if let Some(path) = &a.json {
        let methods: Vec<json::MethodEpisode<'_>> = episodes
            .iter()
            .map(|e| json::MethodEpisode {
                method: &e.method,
                trajectory: e.trajectory,
            })
            .collect();
        let scenario = &scenarios[a.episode];
        let id = (a.preset.as_str(), a.episode, a.seed);
        json::write_replay_json(path, &config, scenario, id, &methods)?;
        println!(
            "Written {} ({} KB): `python -m fairgrasp.rerun {} --rrd episode.rrd` makes a Rerun \
             recording of it",
            path.display(),
            std::fs::metadata(path).map_or(0, |m| m.len() / 1024),
            path.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes the interactive 3D replay page of `episodes` to `out` and says how to open it.
fn write_html(
    out: &Path,
    a: &ReplayArgs,
    names: &[String],
    episodes: &[ReplayEpisode<'_>],
) -> anyhow::Result<()> {
    let title = format!(
        "fairgrasp replay: {} on {} #{}",
        names.join(" vs "),
        a.preset,
        a.episode
    );
    replay3d::write_replay(out, &title, episodes)?;
    let with = if episodes.len() > 1 { "&with=1" } else { "" };
    println!(
        "Written {} ({} KB): open it in a browser, e.g. {}#episode=0&t=0{with}",
        out.display(),
        std::fs::metadata(out).map_or(0, |m| m.len() / 1024),
        out.display()
    );
    Ok(())
}
