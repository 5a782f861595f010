//! `fairgrasp baseline`: the scripted grasp on a preset's seeded scenario set.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets::{self, PRESETS, RENAMED_PRESETS};
use fairgrasp_env::episode::{EvalReport, Policy, evaluate_seeded};
use fairgrasp_evaluate::compare::methods::{script_names, scripts_by_task};
use fairgrasp_evaluate::tune::fragment;
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::{self, Control, ParamValues};
use fairgrasp_types::output::StagedRecording;
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

/// `--script`'s help: each task's scripts by name (the planner's table, [`scripts_by_task`]).
fn script_help() -> String {
    format!(
        "Which script: a control of the preset's task by name ({}); open_loop is each task's \
         open-loop script",
        scripts_by_task()
    )
}

#[derive(Args, Debug)]
pub struct BaselineArgs {
    #[command(flatten)]
    scenarios: ScenarioArgs,
    // Its help (`script_help`) lists each task's scripts from the planner's table; the preset's
    // task picks the control.
    #[arg(long, default_value = "open_loop", help = script_help(), hide_possible_values = true,
          value_parser = clap::builder::PossibleValuesParser::new(script_names()))]
    script: String,
    /// A preset fragment `fairgrasp tune` wrote (its `tuned.toml`): the script runs with the
    /// tuned setting. It must be the script's and tuned on this preset.
    #[arg(long, value_name = "FILE")]
    tuned: Option<PathBuf>,
    /// With `--script tuned_grip`: squeeze this many newtons per finger (0–100] instead of the
    /// preset's `[control] grip_force`: one point of the grid an engineer searches (run it on
    /// a training seed, never on the seed results are reported on).
    #[arg(long, value_name = "N", value_parser = grip_force)]
    grip_force: Option<f64>,
    /// With `--script force_search`: the descent speed [m/s].
    #[arg(long, value_name = "M_PER_S", value_parser = crate::cli::args::finite_number)]
    search_descend_speed: Option<f64>,
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
    /// The values the flags give (`--search-*`, `--grip-force`), by parameter name, with the
    /// flags as the user typed them (for an error).
    fn flag_values(&self) -> (ParamValues, Vec<String>) {
        let mut values = ParamValues::new();
        let mut given = Vec::new();
        for (flag, name, v) in [
            (
                "--search-descend-speed",
                "descend_speed",
                self.search_descend_speed,
            ),
            ("--search-force", "contact_force", self.search_force),
            ("--search-admittance", "admittance", self.search_admittance),
            ("--search-pitch", "pitch", self.search_pitch),
            ("--search-speed", "speed", self.search_speed),
            ("--search-max-radius", "max_radius", self.search_max_radius),
            ("--search-floor-band", "floor_band", self.search_floor_band),
            ("--grip-force", "grip_force", self.grip_force),
        ] {
            if let Some(v) = v {
                values.insert(name.to_string(), v);
                given.push(format!("{flag} {v}"));
            }
        }
        (values, given)
    }

    /// The preset's config with the tuned fragment and the flags' values set for `control`;
    /// a flag of another control, or a value the preset refuses, is refused naming the flag.
    fn control_config(&self, config: &mut EnvConfig, control: &Control) -> anyhow::Result<()> {
        if let Some(path) = &self.tuned {
            let tuned = fragment::apply(config, &self.scenarios.preset, path)?;
            if tuned.cli != control.cli {
                anyhow::bail!(
                    "--tuned {}: a fragment of `{}`, not of --script {}",
                    path.display(),
                    tuned.cli,
                    control.cli
                );
            }
        }
        let (values, given) = self.flag_values();
        if let Some(foreign) = values.keys().find(|n| control.param(n).is_none()) {
            let flag = given
                .iter()
                .find(|g| {
                    g.contains(&foreign.replace('_', "-"))
                        || foreign == "contact_force"
                        || foreign == "grip_force"
                })
                .cloned()
                .unwrap_or_default();
            anyhow::bail!(
                "{flag}: not a parameter of --script {} ({}): the --search-* flags are force_search's, --grip-force tuned_grip's",
                control.cli,
                if control.params.is_empty() {
                    "it has none".to_string()
                } else {
                    control
                        .params
                        .iter()
                        .map(|p| p.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            );
        }
        (control.set)(config, &values);
        config
            .validate()
            .map_err(|e| anyhow::anyhow!("{}: {e}", given.join(", ")))?;
        Ok(())
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
    evaluate_config(a, &config, method, make, extra)
}

/// [`evaluate_and_print`] on `config` (the preset of `a` with a tuned setting, say).
pub fn evaluate_config<P: Policy>(
    a: &ScenarioArgs,
    config: &EnvConfig,
    method: &str,
    make: &(dyn Fn(&EnvConfig) -> P + Sync),
    extra: serde_json::Value,
) -> anyhow::Result<ExitCode> {
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    // Recorded whole or not at all: a failure (a full disk) leaves the folder as it was.
    let staged = match &a.record {
        Some(dir) => Some(StagedRecording::start(dir).map_err(anyhow::Error::msg)?),
        None => None,
    };
    let bar = progress_bar(u64::from(a.episodes), a.json, method);
    let report = evaluate_seeded(
        config,
        a.seed,
        a.episodes as usize,
        threads,
        staged.as_ref().map(StagedRecording::path),
        &|| make(config),
        &|| bar.inc(1),
    )?;
    bar.finish_and_clear();
    if let Some(staged) = staged {
        staged.finish().map_err(anyhow::Error::msg)?;
    }
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
    match (r.mean_steps_to_success, r.mean_cycle_time_s) {
        (Some(s), Some(c)) => println!("  mean steps to success {s:5.1}  (cycle time {c:.1} s)"),
        (Some(s), None) => println!("  mean steps to success {s:5.1}"),
        (None, _) => println!("  mean steps to success   n/a (no success)"),
    }
    if let Some(takt) = r.takt_s {
        println!(
            "  within the {takt} s takt {:5.1} %  (95 % Wilson CI {:.1}–{:.1} %)",
            100.0 * r.within_takt_rate,
            100.0 * r.within_takt_ci_low,
            100.0 * r.within_takt_ci_high
        );
    }
    println!("  collision rate        {:5.1} %", 100.0 * r.collision_rate);
    println!("  mean return           {:7.3}", r.mean_return);
    let breakdown: Vec<String> = r.outcomes.iter().map(|(o, n)| format!("{o} {n}")).collect();
    println!("  outcomes              {}", breakdown.join(", "));
}

pub fn run(a: &BaselineArgs) -> anyhow::Result<ExitCode> {
    let mut config = preset_config(&a.scenarios.preset, a.scenarios.arm)?;
    let task = config.task.kind;
    let Some(control) = controls::control(task, &a.script) else {
        anyhow::bail!(
            "--script {} on preset `{}`: not a control of its task ({}); its scripts are {}",
            a.script,
            a.scenarios.preset,
            task.name(),
            controls::control_names(task).join(", ")
        );
    };
    a.control_config(&mut config, control)?;
    let calibration = CameraCalibration::of(&config).map_err(anyhow::Error::msg)?;
    if control.cli == "calibrated" && !a.scenarios.json {
        print_calibration(&calibration);
    }
    let mut extra = serde_json::Map::new();
    if !control.params.is_empty() {
        let values = (control.values)(&config);
        extra.insert("params".into(), serde_json::to_value(&values)?);
        if control.cli.contains("force_search") {
            extra.insert(
                "search".into(),
                serde_json::to_value(config.task.place.search)?,
            );
        }
        if control.cli == "tuned_grip" {
            extra.insert(
                "grip_force_n".into(),
                serde_json::to_value(values["grip_force"])?,
            );
        }
    }
    if let Some(note) = config.control.tuned.get(control.cli) {
        extra.insert("tuned".into(), serde_json::to_value(note)?);
    }
    if control.cli == "calibrated" {
        extra.insert("calibration".into(), calibration_json(&calibration));
    }
    let make = |config: &EnvConfig| (control.build)(config, &calibration);
    evaluate_config(
        &a.scenarios,
        &config,
        control.report,
        &make,
        serde_json::Value::Object(extra),
    )
}

/// The camera calibration's result as `--json` reports it.
fn calibration_json(calibration: &CameraCalibration) -> serde_json::Value {
    match &calibration.fit {
        Ok(fit) => serde_json::json!({
            "touches": fit.residuals.len(), "rms_m": fit.rms,
            "camera_error": fit.base_in_world.record(),
        }),
        Err(why) => serde_json::json!({"refused": why}),
    }
}

/// The camera calibration's result as a line of text.
fn print_calibration(calibration: &CameraCalibration) {
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
        Err(why) => {
            println!("camera calibration refused ({why}): the script runs on the camera as it is")
        }
    }
}
