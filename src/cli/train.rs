//! `fairgrasp train` and `fairgrasp eval`: the PPO agent.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use burn::tensor::Device;
use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_rl::run::checkpoint;
use fairgrasp_rl::run::train::{TrainConfig, agent_policy, train_with};

use super::baseline::{ScenarioArgs, evaluate_and_print, print_report};

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
    /// Override the config's seed (a --resume without it keeps the run's seed).
    #[arg(long)]
    seed: Option<u64>,
    /// Override the config's total_timesteps.
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=10_000_000_000))]
    timesteps: Option<u64>,
    /// Override the config's max_wall_time_s: stop after this many seconds of this invocation.
    #[arg(long, value_name = "SECONDS", value_parser = crate::cli::args::positive_seconds)]
    max_wall_time: Option<f64>,
}

pub fn run_train(a: &TrainArgs) -> anyhow::Result<ExitCode> {
    let mut config = TrainConfig::from_toml_file(&a.config)?;
    if let Some(s) = a.seed {
        config.seed = s;
    }
    if let Some(t) = a.timesteps {
        config.total_timesteps = t;
    }
    if let Some(t) = a.max_wall_time {
        config.max_wall_time_s = Some(t);
    }
    let run_dir = a.run_dir.clone().unwrap_or_else(|| {
        let stem = a
            .config
            .file_stem()
            .map_or("run".into(), |s| s.to_string_lossy().into_owned());
        Path::new("runs").join(stem)
    });
    if a.resume && a.seed.is_none() {
        config.seed = fairgrasp_rl::run::resume::run_seed(&run_dir, config.seed)?;
    }
    if a.resume
        && !fairgrasp_rl::run::resume::has_checkpoint(&run_dir)
        && run_dir.join("config.toml").exists()
    {
        eprintln!(
            "note: {} holds no checkpoint yet (killed before its first one?): starting it fresh",
            run_dir.display()
        );
    }
    let options = fairgrasp_rl::run::resume::ResumeOptions {
        resume: a.resume,
        accept_config_changes: a.accept_config_changes,
    };
    let mut lines = super::progress::TrainLines::new();
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

#[derive(Args, Debug)]
pub struct EvalArgs {
    /// Checkpoint folder (a run's checkpoints/best or checkpoints/latest). Default: the shipped
    /// residual policy (built into the binary; assets/policies/residual_hard in the sources).
    #[arg(long, value_name = "DIR")]
    policy: Option<PathBuf>,
    /// Ablation: set every policy input whose name starts with NAME to 0 (e.g. `wrist` for the
    /// wrist camera's features of a task-space residual, `cube_moved` for the push). Repeat for
    /// several. An unknown name is refused with the list of input names.
    #[arg(long = "mask-input", value_name = "NAME")]
    mask_input: Vec<String>,
    #[command(flatten)]
    scenarios: ScenarioArgs,
}

pub fn run_eval(a: &EvalArgs) -> anyhow::Result<ExitCode> {
    // The shipped residual policy is built into the binary: found from any folder.
    let policy = match &a.policy {
        Some(p) => p.clone(),
        None => fairgrasp_rl::run::shipped::default_policy()
            .context("unpacking the shipped residual policy")?,
    };
    let (meta, model) = checkpoint::load_model(&policy, &Device::flex())
        .context("loading the policy (pass --policy DIR to choose one)")?;
    let mut masked = Vec::new();
    for prefix in &a.mask_input {
        let found = meta
            .agent
            .input_indices(prefix)
            .map_err(|e| anyhow::anyhow!("--mask-input {prefix}: {e}"))?;
        masked.extend(found);
    }
    let mut method = format!("{} agent ({})", meta.agent.mode, policy.display());
    if !a.mask_input.is_empty() {
        method += &format!(", inputs masked: {}", a.mask_input.join(", "));
    }
    let make =
        |config: &EnvConfig| agent_policy(&meta, &model, config).with_masked_inputs(masked.clone());
    let extra = serde_json::json!({"policy": policy.display().to_string(), "trained_timesteps": meta.timesteps, "masked_inputs": a.mask_input});
    evaluate_and_print(&a.scenarios, &method, &make, extra)
}
