//! `fairgrasp compare`: the baseline and learned policies on identical seeded scenario sets,
//! with the table, compare.csv/json, charts, replays and the notebook in one folder.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, bail};
use burn::tensor::Device;
use clap::Args;
use fairgrasp_env::policy::{EvalReport, Policy, evaluate, run_episode};
use fairgrasp_env::randomize::scenario_set;
use fairgrasp_env::trajectory::Trajectory;
use fairgrasp_env::{EnvConfig, GraspEnv};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_report::compare::{self, Comparison, MethodResult, RecordedEpisode};
use fairgrasp_report::report::slug;
use fairgrasp_report::{build_report, write_atomic};
use fairgrasp_rl::checkpoint::{self, CheckpointMeta};
use fairgrasp_rl::model::ActorCritic;
use fairgrasp_rl::train::agent_policy;

use super::baseline::{ArmArg, preset_config, progress_bar};

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Presets (or .toml env configs) to compare on; repeat the flag for several.
    /// Default: seed, full and hard.
    #[arg(long = "preset", value_name = "NAME")]
    presets: Vec<String>,
    /// Episodes (scenarios) per preset; every method gets the same ones.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    episodes: u32,
    /// Learned policies (checkpoint folders); repeat for several. Default: the shipped residual
    /// and pure-PPO policies in assets/policies/.
    #[arg(long = "policy", value_name = "DIR")]
    policies: Vec<PathBuf>,
    /// Seed of the scenario sets.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    arm: ArmArg,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// Output folder: compare.csv, compare.json, charts, replays, report.md, report.ipynb.
    #[arg(long, value_name = "DIR", default_value = "report")]
    out: PathBuf,
    /// Scenario index (on the last preset) recorded for the episode charts and replays.
    /// Default: the first one where the first two methods end differently, else 0.
    #[arg(long, value_name = "K")]
    episode: Option<usize>,
    /// Print compare.json on stdout instead of the table.
    #[arg(long)]
    json: bool,
}

/// A learned policy loaded from its checkpoint.
struct Learned {
    name: String,
    dir: PathBuf,
    meta: CheckpointMeta,
    model: ActorCritic,
}

/// The shipped policies compared by default.
fn default_policies() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/policies");
    ["residual_hard", "pure_hard"]
        .iter()
        .map(|p| root.join(p).join("checkpoint"))
        .collect()
}

/// The run folder a checkpoint folder belongs to (the nearest ancestor with metrics.csv).
fn run_folder_of(checkpoint: &Path) -> Option<PathBuf> {
    checkpoint
        .ancestors()
        .skip(1)
        .take(2)
        .find(|d| d.join("metrics.csv").is_file())
        .map(Path::to_path_buf)
}

fn load_policies(paths: &[PathBuf]) -> anyhow::Result<Vec<Learned>> {
    let device = Device::flex();
    let mut out: Vec<Learned> = Vec::new();
    for dir in paths {
        let (meta, model) = checkpoint::load_model(dir, &device)
            .with_context(|| format!("loading the policy {}", dir.display()))?;
        let folder = run_folder_of(dir).unwrap_or_else(|| dir.clone());
        let label = folder
            .file_name()
            .map_or("policy".into(), |n| n.to_string_lossy().into_owned());
        let mode = format!("{:?}", meta.agent.mode).to_lowercase();
        let mut name = format!("{mode} PPO: {label}");
        if out.iter().any(|l| l.name == name) {
            name = format!("{name} ({})", out.len() + 1);
        }
        out.push(Learned {
            name,
            dir: dir.clone(),
            meta,
            model,
        });
    }
    Ok(out)
}

/// An evaluation report as the report crate's record.
fn method_result(
    method: &str,
    preset: &str,
    a: &CompareArgs,
    report: &EvalReport,
    policy: Option<&Path>,
) -> anyhow::Result<MethodResult> {
    let mut v = serde_json::to_value(report)?;
    let fields = serde_json::json!({
        "method": method, "preset": preset, "arm": format!("{:?}", a.arm).to_lowercase(),
        "seed": a.seed, "policy": policy.map(|p| p.display().to_string()),
    });
    if let (Some(v), serde_json::Value::Object(f)) = (v.as_object_mut(), fields) {
        v.extend(f);
    }
    Ok(serde_json::from_value(v)?)
}

/// Runs `make`'s policy on every scenario of `config` and returns the report.
fn run_method<P: Policy>(
    config: &EnvConfig,
    scenarios: &[fairgrasp_env::randomize::Scenario],
    threads: usize,
    make: &(dyn Fn() -> P + Sync),
    bar: &indicatif::ProgressBar,
) -> anyhow::Result<EvalReport> {
    Ok(evaluate(config, scenarios, threads, None, make, &|| {
        bar.inc(1)
    })?)
}

pub fn run(a: &CompareArgs) -> anyhow::Result<ExitCode> {
    let presets = if a.presets.is_empty() {
        vec!["seed".to_string(), "full".into(), "hard".into()]
    } else {
        a.presets.clone()
    };
    let policy_paths = if a.policies.is_empty() {
        default_policies()
    } else {
        a.policies.clone()
    };
    if let Some(dup) = presets
        .iter()
        .enumerate()
        .find_map(|(i, p)| presets[..i].contains(p).then_some(p))
    {
        bail!("--preset {dup} is given twice");
    }
    if let Some(k) = a.episode.filter(|&k| k >= a.episodes as usize) {
        bail!(
            "--episode {k}: the scenario sets have {} episodes (0–{})",
            a.episodes,
            a.episodes - 1
        );
    }
    let learned = load_policies(&policy_paths)?;
    let configs: Vec<EnvConfig> = presets
        .iter()
        .map(|p| preset_config(p, a.arm).with_context(|| format!("preset `{p}`")))
        .collect::<anyhow::Result<_>>()?;
    if a.out.is_file() {
        bail!("--out {}: is a file, expected a folder", a.out.display());
    }
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let mut methods = vec!["scripted baseline".to_string()];
    methods.extend(learned.iter().map(|l| l.name.clone()));
    let total = (presets.len() * methods.len()) as u64 * u64::from(a.episodes);
    let bar = progress_bar(total, a.json, "compare");
    let mut results = Vec::new();
    let mut last_scenarios = Vec::new();
    for (preset, config) in presets.iter().zip(&configs) {
        let env = GraspEnv::new(config.clone())?;
        let scenarios = scenario_set(
            config,
            env.model(),
            env.base_in_world(),
            a.seed,
            a.episodes as usize,
        )
        .with_context(|| format!("preset `{preset}`"))?;
        bar.set_message(format!("{preset}: baseline"));
        let make = || ScriptedGrasp::new(config, BaselineConfig::default());
        let report = run_method(config, &scenarios, threads, &make, &bar)?;
        results.push(method_result(&methods[0], preset, a, &report, None)?);
        for l in &learned {
            bar.set_message(format!("{preset}: {}", l.name));
            let make = || agent_policy(&l.meta, &l.model, config);
            let report = run_method(config, &scenarios, threads, &make, &bar)?;
            results.push(method_result(&l.name, preset, a, &report, Some(&l.dir))?);
        }
        last_scenarios = scenarios;
    }
    bar.finish_and_clear();

    // Record one scenario of the last preset for every method.
    let (last_preset, last_config) = (
        presets.last().expect("presets"),
        configs.last().expect("configs"),
    );
    let last: Vec<&MethodResult> = results
        .iter()
        .filter(|r| &r.preset == last_preset)
        .collect();
    let k = a.episode.unwrap_or_else(|| {
        (0..last_scenarios.len())
            .find(|&i| last.len() > 1 && last[0].results[i].outcome != last[1].results[i].outcome)
            .unwrap_or(0)
    });
    let scenario = &last_scenarios[k];
    let mut recorded = Vec::new();
    let mut env = GraspEnv::new(last_config.clone())?;
    for (i, method) in methods.iter().enumerate() {
        let mut trajectory = Trajectory::default();
        let result = if i == 0 {
            let mut p = ScriptedGrasp::new(last_config, BaselineConfig::default());
            run_episode(&mut env, &mut p, scenario, Some(&mut trajectory))?
        } else {
            let l = &learned[i - 1];
            let mut p = agent_policy(&l.meta, &l.model, last_config);
            run_episode(&mut env, &mut p, scenario, Some(&mut trajectory))?
        };
        let stem = format!("{}_{}_ep{k}", slug(method), slug(last_preset));
        trajectory
            .save(&a.out.join("episodes"), &stem)
            .with_context(|| format!("writing {}", a.out.join("episodes").display()))?;
        recorded.push(RecordedEpisode {
            method: method.clone(),
            preset: last_preset.clone(),
            episode: k,
            outcome: serde_json::to_value(result.outcome)?
                .as_str()
                .unwrap_or_default()
                .to_string(),
            trajectory: format!("episodes/{stem}.json"),
        });
    }

    let comparison = Comparison {
        command: std::iter::once("fairgrasp".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>()
            .join(" "),
        presets: presets.clone(),
        methods,
        preset_configs: presets
            .iter()
            .zip(&configs)
            .map(|(p, c)| Ok((p.clone(), toml::to_string(c)?)))
            .collect::<anyhow::Result<_>>()?,
        run_folders: policy_paths
            .iter()
            .filter_map(|p| run_folder_of(p))
            .map(|p| p.display().to_string())
            .collect(),
        recorded,
        results,
    };
    comparison.check().map_err(anyhow::Error::msg)?;
    write_atomic(&a.out.join("compare.json"), comparison.to_json().as_bytes())?;
    write_atomic(
        &a.out.join("compare.csv"),
        compare::to_csv(&comparison).as_bytes(),
    )?;
    let written = build_report(std::slice::from_ref(&a.out), &a.out)?;
    if a.json {
        println!("{}", comparison.to_json());
    } else {
        print!("{}", compare::text_table(&comparison));
        println!(
            "\n{} episodes per preset from seed {}, {:?} arm; 95 % Wilson intervals.",
            a.episodes, a.seed, a.arm
        );
        println!("Written to {}:", a.out.display());
        let mut names: Vec<String> = ["compare.csv", "compare.json"].map(String::from).to_vec();
        names.extend(
            written
                .iter()
                .filter_map(|p| p.strip_prefix(&a.out).ok())
                .map(|p| p.display().to_string()),
        );
        for n in names {
            println!("  {n}");
        }
    }
    Ok(ExitCode::SUCCESS)
}
