//! `fairgrasp export`: one episode (any script or policy, any preset and scenario, or a cube
//! placed by hand) as a servo stream for a real FR3, checked against its limits before anything
//! is written. `fairgrasp playback` ([`super::playback`]) plays such a file in the env.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::Args;
use fairgrasp_env::EnvConfig;
use fairgrasp_env::episode::Outcome;
use fairgrasp_env::scenario::{Scenario, scenario_set};
use fairgrasp_evaluate::compare::methods::{Method, script_names, scripts_by_task};
use fairgrasp_evaluate::export::{ExportError, export_episode};
use fairgrasp_kinematics::Pose;
use fairgrasp_planner::stream::check::peaks;
use fairgrasp_planner::stream::file::{self, Format};
use fairgrasp_planner::stream::{
    DEFAULT_PERIOD_SEC, MAX_STEP_DEG, PERIOD_RANGE_SEC, ServoStream, StreamLimits,
};
use fairgrasp_types::ArmSimulation;
use fairgrasp_types::fs::write_atomic;
use serde_json::{Value, json};

use super::args::{OutputArgs, finite_number, pose_from, print_json};
use super::baseline::preset_config;

/// Where the episode comes from: the preset, its scenario and the cell (shared with playback).
#[derive(Args, Debug)]
pub struct EpisodeArgs {
    /// Preset name or a .toml env config (e.g. the one `fairgrasp calibrate points --out` wrote)
    /// [default: sector; playback: the file's].
    #[arg(long, value_parser = super::args::preset)]
    pub preset: Option<String>,
    /// Index of the scenario in the preset's seeded set, 0–999999 (the episode `compare --seed
    /// S` calls N) [default: 0; playback: the file's].
    #[arg(long, value_name = "N", value_parser = super::args::scenario_index)]
    pub episode: Option<usize>,
    /// Seed of the scenario set, 0–9007199254740991 (2⁵³ − 1) [default: 0; playback: the file's].
    #[arg(long, value_parser = super::args::seed)]
    pub seed: Option<u64>,
    /// The real cell's mount: base_link in the world, x y z [m] roll pitch yaw (radians, or
    /// degrees with --deg), as in `fairgrasp frames`; replaces the preset's `[arm]` mount.
    #[arg(long, num_args = 6, allow_hyphen_values = true, value_parser = finite_number,
          value_names = ["X", "Y", "Z", "ROLL", "PITCH", "YAW"])]
    pub base: Option<Vec<f64>>,
    /// Put the cube here instead of where the scenario draws it: x y [m] in the table frame (on
    /// the table top under the base, x along its heading) and its yaw (radians, or --deg).
    #[arg(long, num_args = 3, allow_hyphen_values = true, value_parser = finite_number,
          value_names = ["X", "Y", "YAW"])]
    pub cube: Option<Vec<f64>>,
}

#[derive(Args, Debug)]
pub struct ExportArgs {
    #[command(flatten)]
    pub episode: EpisodeArgs,
    // Its help (`method_help`) lists each task's scripts from the planner's table; clap accepts
    // any of the table's names, and the preset's task picks the control.
    #[arg(long, conflicts_with = "policy", help = method_help(), hide_possible_values = true,
          value_parser = clap::builder::PossibleValuesParser::new(script_names()))]
    method: Option<String>,
    /// The policy that grasps, as every command takes one: a shipped policy by name
    /// (residual_nudged, pure_full, …), a policy folder (assets/policies/residual_nudged), a
    /// checkpoint folder (…/checkpoint) or a run folder (its checkpoints/best).
    #[arg(long, value_name = "NAME")]
    policy: Option<String>,
    /// Servo period [s]: 0.001–0.016 (FAIRINO's driver).
    #[arg(long, default_value_t = DEFAULT_PERIOD_SEC, value_parser = finite_number)]
    period: f64,
    /// How long the final sample is repeated at the end, so the arm settles [s].
    #[arg(long, default_value_t = 0.25, value_parser = finite_number)]
    hold: f64,
    /// Leave out the gripper's commands, which are written by default (JSON: a `gripper` list
    /// of events; CSV: a `gripper_command` column; .npy: FILE.gripper.npy beside it): an
    /// arm-only stream, which playback refuses (it cannot grasp).
    #[arg(long)]
    no_gripper: bool,
    /// Write the gripper's commands: the default (accepted so that older commands still run).
    #[arg(long, conflicts_with = "no_gripper")]
    gripper: bool,
    /// Export an episode that failed in the simulator (refused by default: a failed grasp
    /// may collide).
    #[arg(long)]
    allow_failure: bool,
    /// The file to write: .json (the ROS 2 driver's `stream_servo_j` goal: period_sec and
    /// joints_deg), .csv or .npy (N×6 degrees). A new file: an existing one is never replaced.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    #[command(flatten)]
    output: OutputArgs,
}

/// `--method`'s help: each task's scripts by name (the planner's table, [`scripts_by_task`]).
fn method_help() -> String {
    format!(
        "The script that grasps, a control of the preset's task by name ({}) [default: open_loop, \
         unless --policy]",
        scripts_by_task()
    )
}

/// Where an episode happens, flags parsed (angles in radians); `None`: not given.
pub struct Place {
    pub preset: Option<String>,
    pub episode: Option<usize>,
    pub seed: Option<u64>,
    pub base: Option<Pose>,
    /// The cube's x, y \[m\] in the table frame and yaw \[rad\].
    pub cube: Option<[f64; 3]>,
}

impl Place {
    /// The flags of `a`, angles converted per `--deg`.
    pub fn from_args(a: &EpisodeArgs, out: &OutputArgs) -> anyhow::Result<Place> {
        let base = a
            .base
            .as_ref()
            .map(|b| pose_from(b, out, "--base"))
            .transpose()?;
        Ok(Place {
            preset: a.preset.clone(),
            episode: a.episode,
            seed: a.seed,
            base,
            cube: a.cube.as_ref().map(|c| [c[0], c[1], out.angle(c[2])]),
        })
    }
}

/// The cell and scenario a [`Place`] names, with defaults (`sector`, episode 0, set 0).
pub struct Chosen {
    pub preset: String,
    pub episode: usize,
    pub seed: u64,
    pub base: Option<Pose>,
    pub config: EnvConfig,
    pub scenario: Scenario,
}

/// Resolves the preset, the mount and the scenario of `p`.
pub fn choose(p: &Place) -> anyhow::Result<Chosen> {
    // A playback's file may name a preset by an old name: the current one is shown.
    let preset = super::args::preset_name(p.preset.as_deref().unwrap_or("sector"));
    let (episode, seed) = (p.episode.unwrap_or(0), p.seed.unwrap_or(0));
    let mut config = preset_config(&preset, ArmSimulation::Servo)
        .with_context(|| format!("preset `{preset}`"))?;
    if let Some(pose) = &p.base {
        config.arm.base_xyz = pose.xyz();
        config.arm.base_rpy = pose.rpy();
        config.validate().context("--base")?;
    }
    let mut scenario = *scenario_set(&config, seed, episode + 1)
        .with_context(|| format!("preset `{preset}`: drawing scenario {episode}"))?
        .last()
        .expect("episode + 1 scenarios");
    if let Some([x, y, yaw]) = p.cube {
        scenario.object_xy = [x, y];
        scenario.object_yaw = yaw;
    }
    Ok(Chosen {
        preset,
        episode,
        seed,
        base: p.base,
        config,
        scenario,
    })
}

pub fn run(a: &ExportArgs) -> anyhow::Result<ExitCode> {
    if !PERIOD_RANGE_SEC.contains(&a.period) {
        bail!(
            "--period {}: a servo period is 0.001–0.016 s (FAIRINO's driver)",
            a.period
        );
    }
    if !(0.0..=10.0).contains(&a.hold) {
        bail!("--hold {}: 0–10 s", a.hold);
    }
    let Some(format) = Format::of(&a.out) else {
        bail!("--out {}: name a .json, .csv or .npy file", a.out.display());
    };
    let gripper = !a.no_gripper;
    let sidecar = (gripper && format == Format::Npy).then(|| a.out.with_extension("gripper.npy"));
    for path in std::iter::once(&a.out).chain(&sidecar) {
        if path.exists() {
            bail!(
                "{}: the file exists; choose a new name (it is never replaced)",
                path.display()
            );
        }
    }
    let chosen = choose(&Place::from_args(&a.episode, &a.output)?)?;
    let name = match (&a.method, &a.policy) {
        (Some(m), _) => m.clone(),
        (None, Some(p)) => p.clone(),
        (None, None) => "open_loop".into(),
    };
    let method = Method::resolve(&name, chosen.config.task.kind)?;
    let model = fairgrasp_env::cell::Cell::from_config(&chosen.config).model;
    let limits = StreamLimits::of(&model);
    let hold_samples = (a.hold / a.period).round() as usize;
    let exported = match export_episode(
        &chosen.config,
        &chosen.scenario,
        method,
        a.period,
        hold_samples,
        &limits,
    ) {
        Err(ExportError::Limit(v)) => bail!("{name} on {} #{}: {v}", chosen.preset, chosen.episode),
        other => other?,
    };
    let outcome = exported.outcome;
    if outcome != Outcome::Success && !a.allow_failure {
        bail!(
            "{name} on {} #{} ended in {outcome} after {} steps in the simulator: nothing was \
             written (a failed grasp is not sent to a real arm; --allow-failure writes it anyway)",
            chosen.preset,
            chosen.episode,
            exported.steps
        );
    }
    let mut stream = exported.resampled.stream.clone();
    if !gripper {
        stream.gripper.clear();
    }
    let source = json!({
        "preset": chosen.preset, "episode": chosen.episode, "seed": chosen.seed,
        "scenario_seed": chosen.scenario.seed, "method": name,
        "base_in_world": chosen.base.map(|b| [b.xyz(), b.rpy()].concat()),
        "cube": a.episode.cube.as_ref().map(|_| json!({
            "xy_m": chosen.scenario.object_xy, "yaw_rad": chosen.scenario.object_yaw})),
        "outcome": outcome.to_string(), "steps": exported.steps,
        "episode_sec": exported.resampled.episode_sec,
        "stretched_segments": exported.resampled.stretched_segments,
    });
    write_stream(&a.out, format, &stream, &model, &source, sidecar.as_deref())?;
    report(a, &stream, &source, &limits)?;
    Ok(ExitCode::SUCCESS)
}

fn write_stream(
    out: &Path,
    format: Format,
    stream: &ServoStream,
    model: &fairgrasp_kinematics::ArmModel,
    source: &Value,
    sidecar: Option<&Path>,
) -> anyhow::Result<()> {
    let bytes = match format {
        Format::Json => file::to_json(stream, model, source),
        Format::Csv => file::to_csv(stream),
        Format::Npy => file::joints_npy(stream),
    };
    write_atomic(out, &bytes).with_context(|| format!("writing {}", out.display()))?;
    if let Some(path) = sidecar {
        write_atomic(path, &file::gripper_npy(stream))
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

fn report(
    a: &ExportArgs,
    stream: &ServoStream,
    source: &Value,
    limits: &StreamLimits,
) -> anyhow::Result<()> {
    let p = peaks(&stream.joints, stream.period_sec);
    if a.output.json {
        print_json(&json!({
            "out": a.out, "samples": stream.joints.len(), "period_sec": stream.period_sec,
            "duration_sec": stream.duration_sec(), "hold_samples": stream.hold_samples,
            "gripper_events": stream.gripper.len(), "peaks": p, "source": source,
        }));
        return Ok(());
    }
    println!(
        "{} on {} #{} (scenario seed {}): {} in {} steps ({:.2} s)",
        source["method"].as_str().unwrap_or("?"),
        source["preset"].as_str().unwrap_or("?"),
        source["episode"],
        source["scenario_seed"],
        source["outcome"].as_str().unwrap_or("?"),
        source["steps"],
        source["episode_sec"].as_f64().unwrap_or(0.0)
    );
    let stretched = source["stretched_segments"].as_u64().unwrap_or(0);
    println!(
        "stream: {} samples every {} ms ({:.2} s, the last {} holding), {} gripper events{}",
        stream.joints.len(),
        stream.period_sec * 1e3,
        stream.duration_sec(),
        stream.hold_samples,
        stream.gripper.len(),
        match stretched {
            0 => String::new(),
            1 => "; 1 env step took longer to stay within the limits".into(),
            n => format!("; {n} env steps took longer to stay within the limits"),
        }
    );
    let vmax = limits
        .max_velocity
        .iter()
        .cloned()
        .fold(f64::INFINITY, f64::min);
    println!(
        "checked: largest step {:.3}° per sample (limit {MAX_STEP_DEG}°), velocity {:.2} rad/s \
         (FR3: {vmax:.2}), acceleration {:.2} rad/s² (limit {:.0}); joints within the soft limits",
        p.step_deg, p.velocity_rad_s, p.acceleration_rad_s2, limits.max_acceleration
    );
    let first: Vec<String> = stream.joints[0]
        .iter()
        .map(|v| format!("{:.2}", v.to_degrees()))
        .collect();
    println!(
        "start (move there first, e.g. MoveJ): [{}] deg",
        first.join(", ")
    );
    println!("written {}", a.out.display());
    Ok(())
}
