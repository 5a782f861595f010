//! `fairgrasp eval`: a trained agent (a checkpoint folder, or the shipped residual policy) on a
//! preset's seeded scenarios, run without burn (`fairgrasp_policy::checkpoint`).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_policy::checkpoint::{actor_policy, load_actor};

use super::baseline::{ScenarioArgs, evaluate_and_print};

#[derive(Args, Debug)]
pub struct EvalArgs {
    /// The policy, as every command takes one: a shipped policy by name (residual_nudged,
    /// pure_full, …; built into the binary), a policy folder (assets/policies/residual_nudged),
    /// a checkpoint folder (…/checkpoint, a run's checkpoints/latest) or a run folder (its
    /// checkpoints/best). Default: residual_hard.
    #[arg(long, value_name = "NAME")]
    policy: Option<String>,
    /// Ablation: set every policy input whose name starts with NAME to 0 (e.g. `wrist` for the
    /// wrist camera's features of a task-space residual, `cube_moved` for the push). Repeat for
    /// several. An unknown name is refused with the list of input names.
    #[arg(long = "mask-input", value_name = "NAME")]
    mask_input: Vec<String>,
    /// Also draw what a squeezing residual learned (`[agent] squeeze = true`): each episode's
    /// grip force as the lift began against the squeeze its cube needed (mass and friction),
    /// as FILE.png, with the rows in FILE.csv. Runs the episodes a second time.
    #[arg(long = "squeeze-chart", value_name = "FILE.png")]
    squeeze_chart: Option<PathBuf>,
    #[command(flatten)]
    scenarios: ScenarioArgs,
}

impl EvalArgs {
    /// Whether the evaluation writes files (`--record DIR`, `--squeeze-chart FILE.png`).
    pub(super) fn writes_files(&self) -> bool {
        self.scenarios.record.is_some() || self.squeeze_chart.is_some()
    }
}

pub fn run_eval(a: &EvalArgs) -> anyhow::Result<ExitCode> {
    // The shipped residual policy is built into the binary: found from any folder.
    let policy = match &a.policy {
        Some(p) => super::args::policy_folder(p)?,
        None => fairgrasp_policy::shipped::default_policy()
            .context("unpacking the shipped residual policy")?,
    };
    let (meta, actor) =
        load_actor(&policy).context("loading the policy (pass --policy NAME to choose one)")?;
    let mut masked = Vec::new();
    let env = super::baseline::preset_config(&a.scenarios.preset, a.scenarios.arm)?;
    for prefix in &a.mask_input {
        let found = meta
            .agent
            .input_indices(&env, prefix)
            .map_err(|e| anyhow::anyhow!("--mask-input {prefix}: {e}"))?;
        masked.extend(found);
    }
    let shown = a
        .policy
        .clone()
        .unwrap_or_else(|| policy.display().to_string());
    let mut method = format!("{} agent ({shown})", meta.agent.mode);
    if !a.mask_input.is_empty() {
        method += &format!(", inputs masked: {}", a.mask_input.join(", "));
    }
    let make =
        |config: &EnvConfig| actor_policy(&meta, &actor, config).with_masked_inputs(masked.clone());
    if let Some(png) = &a.squeeze_chart {
        super::squeeze_chart::check_paths(png)?;
    }
    let extra = serde_json::json!({"policy": policy.display().to_string(), "trained_timesteps": meta.timesteps, "masked_inputs": a.mask_input});
    let code = evaluate_and_print(&a.scenarios, &method, &make, extra)?;
    if let Some(png) = &a.squeeze_chart {
        super::squeeze_chart::write(&a.scenarios, &method, png, &make)?;
    }
    Ok(code)
}
