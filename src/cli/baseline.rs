//! `fairgrasp baseline`: the scripted grasp on a preset's seeded scenario set.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use fairgrasp_env::config::presets::{self, PRESETS, RENAMED_PRESETS};
use fairgrasp_env::episode::{EvalReport, Policy, evaluate_seeded};
use fairgrasp_env::{EnvConfig, TaskKind};
use fairgrasp_planner::{
    BaselineConfig, CalibratedScript, CameraCalibration, ClosedLoopGrasp, ScriptedGrasp,
    ScriptedPlace, SearchParams, TunedGripScript,
};
use fairgrasp_types::{ArmSimulation, MethodResult};
use indicatif::{ProgressBar, ProgressStyle};

fn preset_help() -> String {
    let names: Vec<String> = PRESETS
        .iter()
        .map(|(n, _, d)| format!("{n} ({d})"))
        .collect();
    let renamed: Vec<String> = RENAMED_PRESETS
        .iter()
        .map(|(old, new)| format!("{old} is the old name of {new}"))
        .collect();
    format!(
        "Preset name or a .toml file: {} ({}, still accepted)",
        names.join("; "),
        renamed.join(", ")
    )
}

/// The scenario set a policy is evaluated on, and how the result is shown.
#[derive(Args, Debug)]
pub struct ScenarioArgs {
    #[arg(long, default_value = "sector", value_parser = crate::cli::args::preset, help = preset_help())]
    pub preset: String,
    /// Episodes (scenarios) to run, 1–1000000.
    #[arg(long, default_value_t = 100, value_parser = crate::cli::args::episode_count)]
    pub episodes: u32,
    /// Seed of the scenario set, 0–9007199254740991 (2⁵³ − 1): the same seed gives the same scenarios for
    /// every policy.
    #[arg(long, default_value_t = 0, value_parser = crate::cli::args::seed)]
    pub seed: u64,
    /// Arm simulation.
    #[arg(long, value_enum, default_value = "servo")]
    pub arm: ArmSimulation,
    /// Worker threads, 1–256 (default: all cores).
    #[arg(long, value_parser = crate::cli::args::thread_count)]
    pub threads: Option<usize>,
    /// Write each episode's trajectory (CSV and JSON) into this folder: a new or empty one (a
    /// folder holding an earlier recording is refused: the two would mix).
    #[arg(long, value_name = "DIR")]
    pub record: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Which scripted grasp runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ScriptArg {
    /// Plans once from the first observation (the baseline).
    #[value(name = "open_loop")]
    OpenLoop,
    /// Re-plans when the observed cube moves, retries a missed grasp once.
    #[value(name = "closed_loop")]
    ClosedLoop,
    /// The closed loop on the cube's true pose (the ceiling).
    Oracle,
    /// The open-loop script after a simulated camera calibration (8 touched marker spots).
    Calibrated,
    /// The open-loop script squeezing the grip tuned for the preset (`[control] grip_force`;
    /// `--grip-force` sets another, for a tuning grid).
    #[value(name = "tuned_grip")]
    TunedGrip,
    /// The place task: the open-loop script with a force-guided spiral search in place of the
    /// lower (`--search-*` set its parameters, for a tuning grid).
    #[value(name = "force_search")]
    ForceSearch,
    /// The place task: the force search in closed loop (the cube re-observed in the hand before
    /// the place is planned). `closed_loop` on a place preset is the closed-loop place without
    /// the search.
    #[value(name = "closed_loop_force_search")]
    ClosedLoopForceSearch,
}

#[derive(Args, Debug)]
pub struct BaselineArgs {
    #[command(flatten)]
    scenarios: ScenarioArgs,
    /// Which script: open_loop (the baseline), closed_loop, oracle, calibrated or tuned_grip; on
    /// a place preset open_loop, force_search, closed_loop or closed_loop_force_search.
    #[arg(long, value_enum, default_value = "open_loop")]
    script: ScriptArg,
    /// With `--script tuned_grip`: squeeze this many newtons per finger (0–100] instead of the
    /// preset's `[control] grip_force`: one point of the grid an engineer searches (run it on
    /// a training seed, never on the seed results are reported on).
    #[arg(long, value_name = "N", value_parser = grip_force)]
    grip_force: Option<f64>,
    /// With `--script force_search`: the touch threshold of the wrist force [N].
    #[arg(long, value_name = "N", value_parser = crate::cli::args::finite_number)]
    search_force: Option<f64>,
    /// With `--script force_search`: the spiral's pitch [m per turn].
    #[arg(long, value_name = "M", value_parser = crate::cli::args::finite_number)]
    search_pitch: Option<f64>,
    /// With `--script force_search`: the spiral's speed [m/s].
    #[arg(long, value_name = "M_PER_S", value_parser = crate::cli::args::finite_number)]
    search_speed: Option<f64>,
    /// With `--script force_search`: the press's admittance while spiralling [m/s per N].
    #[arg(long, value_name = "M_PER_S_PER_N", value_parser = crate::cli::args::finite_number)]
    search_admittance: Option<f64>,
    /// With `--script force_search`: the largest spiral radius searched before the cube is let
    /// go where it is [m].
    #[arg(long, value_name = "M", value_parser = crate::cli::args::finite_number)]
    search_max_radius: Option<f64>,
    /// With `--script force_search`: a touch within this height above the pocket's floor counts
    /// as the cube on the floor, a higher one as the rim (the spiral starts) [m]; default: the
    /// preset's, else half the wall.
    #[arg(long, value_name = "M", value_parser = crate::cli::args::finite_number)]
    search_floor_band: Option<f64>,
}

impl BaselineArgs {
    /// The force search's parameters: the preset's tuned ones with the `--search-*` flags given.
    /// The flags a family's tuning holds (force, pitch, speed, floor band) are checked by the
    /// preset's own rule (`[task.place.search]`); admittance and largest radius here.
    fn search_params(&self, config: &EnvConfig) -> anyhow::Result<SearchParams> {
        let mut tuned = config.clone();
        let t = &mut tuned.task.place.search;
        let mut given_flags = Vec::new();
        for (flag, given, slot) in [
            ("--search-force", self.search_force, &mut t.contact_force),
            ("--search-pitch", self.search_pitch, &mut t.pitch),
            ("--search-speed", self.search_speed, &mut t.speed),
        ] {
            if let Some(v) = given {
                *slot = v;
                given_flags.push(format!("{flag} {v}"));
            }
        }
        if let Some(band) = self.search_floor_band {
            t.floor_band = Some(band);
            given_flags.push(format!("--search-floor-band {band}"));
        }
        tuned
            .validate()
            .map_err(|e| anyhow::anyhow!("{}: {e}", given_flags.join(", ")))?;
        let mut p = SearchParams::tuned_for(&tuned);
        for (flag, given, slot, lo, hi) in [
            (
                "--search-admittance",
                self.search_admittance,
                &mut p.admittance,
                0.0001,
                0.05,
            ),
            (
                "--search-max-radius",
                self.search_max_radius,
                &mut p.max_radius,
                0.001,
                0.05,
            ),
        ] {
            if let Some(v) = given {
                if !(lo..=hi).contains(&v) {
                    anyhow::bail!("{flag} {v}: must be in [{lo}, {hi}]");
                }
                *slot = v;
            }
        }
        Ok(p)
    }
}

/// A grip force \[N\] in (0, 100].
fn grip_force(text: &str) -> Result<f64, String> {
    let f: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if f > 0.0 && f <= 100.0 {
        Ok(f)
    } else {
        Err(format!(
            "{f} N: must be in (0, 100] N (gripper.force's range)"
        ))
    }
}

/// Runs a fresh policy from `make` on the scenario set of `a`, and prints the report (text, or
/// one JSON object extended with `extra`).
pub fn evaluate_and_print<P: Policy>(
    a: &ScenarioArgs,
    method: &str,
    make: &(dyn Fn(&EnvConfig) -> P + Sync),
    extra: serde_json::Value,
) -> anyhow::Result<ExitCode> {
    let config = preset_config(&a.preset, a.arm)?;
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if let Some(dir) = &a.record {
        fairgrasp_types::output::check_record_folder(dir).map_err(anyhow::Error::msg)?;
    }
    let bar = progress_bar(u64::from(a.episodes), a.json, method);
    let report = evaluate_seeded(
        &config,
        a.seed,
        a.episodes as usize,
        threads,
        a.record.as_deref(),
        &|| make(&config),
        &|| bar.inc(1),
    )?;
    bar.finish_and_clear();
    if a.json {
        let mut v = report_json(method, &a.preset, a.arm, a.seed, &report)?;
        if let (Some(v), serde_json::Value::Object(extra)) = (v.as_object_mut(), extra) {
            v.extend(extra);
        }
        println!("{v}");
    } else {
        print_report(method, &a.preset, a.arm, a.seed, &report);
        if let Some(dir) = &a.record {
            println!(
                "  trajectories          {}/episode_NNNN.csv and .json",
                dir.display()
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// The environment config for a preset and arm.
pub fn preset_config(preset: &str, arm: ArmSimulation) -> anyhow::Result<EnvConfig> {
    let mut config = presets::load(preset)?;
    config.arm.model = arm;
    Ok(config)
}

/// A progress bar on stderr when it is a terminal and the output is not JSON.
pub fn progress_bar(len: u64, json: bool, label: &str) -> ProgressBar {
    if json || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} episodes, {per_sec}, eta {eta}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar.set_message(label.to_string());
    bar
}

/// The report as the one JSON object the CLI prints: a [`MethodResult`], as in compare.json.
pub fn report_json(
    method: &str,
    preset: &str,
    arm: ArmSimulation,
    seed: u64,
    r: &EvalReport,
) -> anyhow::Result<serde_json::Value> {
    Ok(serde_json::to_value(MethodResult {
        method: method.to_string(),
        preset: preset.to_string(),
        arm,
        seed,
        policy: None,
        report: r.clone(),
    })?)
}

/// The report as text.
pub fn print_report(method: &str, preset: &str, arm: ArmSimulation, seed: u64, r: &EvalReport) {
    println!(
        "{method} on preset `{preset}` ({} arm), {} episodes from seed {seed}",
        arm, r.episodes
    );
    println!(
        "  success rate          {:5.1} %  (95 % Wilson CI {:.1}–{:.1} %)",
        100.0 * r.success_rate,
        100.0 * r.ci_low,
        100.0 * r.ci_high
    );
    match r.mean_steps_to_success {
        Some(s) => println!("  mean steps to success {s:5.1}"),
        None => println!("  mean steps to success   n/a (no success)"),
    }
    println!("  collision rate        {:5.1} %", 100.0 * r.collision_rate);
    println!("  mean return           {:7.3}", r.mean_return);
    let breakdown: Vec<String> = r.outcomes.iter().map(|(o, n)| format!("{o} {n}")).collect();
    println!("  outcomes              {}", breakdown.join(", "));
}

pub fn run(a: &BaselineArgs) -> anyhow::Result<ExitCode> {
    let none = serde_json::json!({});
    if a.grip_force.is_some() && a.script != ScriptArg::TunedGrip {
        anyhow::bail!("--grip-force is the tuned_grip script's: add --script tuned_grip");
    }
    let config = preset_config(&a.scenarios.preset, a.scenarios.arm)?;
    if config.task.kind == TaskKind::Place {
        let params = a.search_params(&config)?;
        return match a.script {
            ScriptArg::OpenLoop => {
                let make = |config: &EnvConfig| ScriptedPlace::new(config);
                evaluate_and_print(&a.scenarios, "place script", &make, none)
            }
            ScriptArg::ForceSearch => {
                let make = |config: &EnvConfig| ScriptedPlace::with_search(config, params);
                let extra = serde_json::json!({ "search": params });
                evaluate_and_print(&a.scenarios, "place script + force search", &make, extra)
            }
            ScriptArg::ClosedLoop => {
                let make = |config: &EnvConfig| ScriptedPlace::new(config).reobserving();
                evaluate_and_print(&a.scenarios, "closed-loop place", &make, none)
            }
            ScriptArg::ClosedLoopForceSearch => {
                let make =
                    |config: &EnvConfig| ScriptedPlace::with_search(config, params).reobserving();
                let extra = serde_json::json!({ "search": params });
                let name = "closed-loop place + force search";
                evaluate_and_print(&a.scenarios, name, &make, extra)
            }
            _ => anyhow::bail!(
                "--preset {}: the place task's scripts are open_loop, force_search, closed_loop \
                 and closed_loop_force_search; the other controls are lift scripts",
                a.scenarios.preset
            ),
        };
    }
    match a.script {
        ScriptArg::ForceSearch | ScriptArg::ClosedLoopForceSearch => {
            anyhow::bail!(
                "--script force_search and closed_loop_force_search are the place task's: give a place preset"
            )
        }
        ScriptArg::TunedGrip => {
            let make = |config: &EnvConfig| {
                let force = a.grip_force.or(config.control.grip_force);
                TunedGripScript::with_grip(config, force)
            };
            let config = preset_config(&a.scenarios.preset, a.scenarios.arm)?;
            let force = a.grip_force.or(config.control.grip_force);
            let extra =
                serde_json::json!({ "grip_force_n": force.unwrap_or(config.gripper.force) });
            evaluate_and_print(&a.scenarios, "tuned_grip", &make, extra)
        }
        ScriptArg::OpenLoop => {
            let make = |config: &EnvConfig| ScriptedGrasp::new(config, BaselineConfig::default());
            evaluate_and_print(&a.scenarios, "baseline", &make, none)
        }
        ScriptArg::ClosedLoop => {
            let make = |config: &EnvConfig| ClosedLoopGrasp::observed(config);
            evaluate_and_print(&a.scenarios, "closed_loop", &make, none)
        }
        ScriptArg::Oracle => {
            let make = |config: &EnvConfig| ClosedLoopGrasp::oracle(config);
            evaluate_and_print(&a.scenarios, "oracle", &make, none)
        }
        ScriptArg::Calibrated => {
            let config = preset_config(&a.scenarios.preset, a.scenarios.arm)?;
            let calibration = CameraCalibration::of(&config).map_err(anyhow::Error::msg)?;
            let extra = match &calibration.fit {
                Ok(fit) => serde_json::json!({"calibration": {
                    "touches": fit.residuals.len(), "rms_m": fit.rms,
                    "camera_error": fit.base_in_world.record(),
                }}),
                Err(why) => serde_json::json!({"calibration": {"refused": why}}),
            };
            if !a.scenarios.json {
                match &calibration.fit {
                    Ok(fit) => {
                        let (dp, dr) = fit.base_in_world.distance_to(&Default::default());
                        println!(
                            "camera calibrated from {} touches (RMS {:.2} mm): the fitted error moves the base origin {:.1} mm and turns {:.2}°",
                            fit.residuals.len(),
                            fit.rms * 1e3,
                            dp * 1e3,
                            dr.to_degrees()
                        );
                    }
                    Err(why) => println!(
                        "camera calibration refused ({why}): the script runs on the camera as it is"
                    ),
                }
            }
            let make = |config: &EnvConfig| CalibratedScript::new(config, calibration.clone());
            evaluate_and_print(&a.scenarios, "calibrated", &make, extra)
        }
    }
}
