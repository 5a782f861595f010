//! `fairgrasp playback`: an exported stream (`fairgrasp export`) played in the env, the servo
//! arm tracking its samples, checked against the FR3's limits first like any file about to
//! reach a controller.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::Args;
use fairgrasp_env::TaskEnv;
use fairgrasp_env::episode::Outcome;
use fairgrasp_kinematics::Pose;
use fairgrasp_planner::stream::file::{Format, parse};
use fairgrasp_planner::stream::{StreamLimits, check_stream, play};
use fairgrasp_types::fs::read_text_bounded;
use serde_json::{Value, json};

use super::args::{OutputArgs, print_json};
use super::export::{EpisodeArgs, Place, choose};

/// The largest stream file read \[bytes\] (a 10-minute stream at 1 ms is about 40 MB).
const MAX_STREAM_BYTES: u64 = 256 << 20;

#[derive(Args, Debug)]
pub struct PlaybackArgs {
    /// The exported stream: .json (its `source` gives the preset, episode, seed, mount and cube,
    /// each overridable by the flags below) or .csv (give --preset and --episode).
    file: PathBuf,
    #[command(flatten)]
    episode: EpisodeArgs,
    #[command(flatten)]
    output: OutputArgs,
}

pub fn run(a: &PlaybackArgs) -> anyhow::Result<ExitCode> {
    let shown = a.file.display();
    let Some(format) = Format::of(&a.file) else {
        bail!("{shown}: playback reads a .json or .csv stream (from `fairgrasp export`)");
    };
    let text = read_text_bounded(&a.file, MAX_STREAM_BYTES).with_context(|| shown.to_string())?;
    let (stream, source) = parse(&text, format).with_context(|| shown.to_string())?;
    let place = with_source(Place::from_args(&a.episode, &a.output)?, &source);
    if place.preset.is_none() || place.episode.is_none() {
        bail!(
            "{shown} does not say which scenario it grasps in (a CSV): give --preset and --episode"
        );
    }
    let chosen = choose(&place)?;
    let model = fairgrasp_env::cell::Cell::from_config(&chosen.config).model;
    let limits = StreamLimits::of(&model);
    check_stream(&stream.joints, stream.period_sec, &limits)
        .map_err(|v| anyhow::anyhow!("{shown}: {v}; not played (a controller must not get it)"))?;
    let mut env = TaskEnv::new(chosen.config.clone())?;
    let report = play(&mut env, &chosen.scenario, &stream).with_context(|| shown.to_string())?;
    let exported = source["outcome"].as_str();
    let ok = report.outcome == Outcome::Success;
    if a.output.json {
        print_json(&json!({
            "file": a.file, "preset": chosen.preset, "episode": chosen.episode, "seed": chosen.seed,
            "outcome": report.outcome.to_string(), "steps": report.steps,
            "exported_outcome": exported, "exported_steps": source["steps"],
            "max_tracking_error_deg": report.max_tracking_error.to_degrees(),
            "start_offset_deg": report.start_offset.to_degrees(),
        }));
    } else {
        println!(
            "{shown}: {} samples every {} ms on {} #{} (set {})",
            stream.joints.len(),
            stream.period_sec * 1e3,
            chosen.preset,
            chosen.episode,
            chosen.seed
        );
        let exported = match exported {
            Some(o) => format!(" (exported: {o} in {} steps)", source["steps"]),
            None => String::new(),
        };
        println!(
            "playback: {} in {} steps{exported}",
            report.outcome, report.steps
        );
        println!(
            "the servo arm stayed within {:.3}° of the stream; it started {:.3}° from the \
             scenario's own start joints",
            report.max_tracking_error.to_degrees(),
            report.start_offset.to_degrees()
        );
    }
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// `place` with what the file's `source` says (radians) filled in where a flag is not given.
fn with_source(place: Place, source: &Value) -> Place {
    let numbers =
        |v: &Value| -> Option<Vec<f64>> { v.as_array()?.iter().map(Value::as_f64).collect() };
    Place {
        preset: place.preset.or(source["preset"].as_str().map(String::from)),
        episode: place
            .episode
            .or(source["episode"].as_u64().map(|v| v as usize)),
        seed: place.seed.or(source["seed"].as_u64()),
        base: place.base.or_else(|| {
            let b: [f64; 6] = numbers(&source["base_in_world"])?.try_into().ok()?;
            Pose::try_from_xyz_rpy([b[0], b[1], b[2]], [b[3], b[4], b[5]]).ok()
        }),
        cube: place.cube.or_else(|| {
            let [x, y]: [f64; 2] = numbers(&source["cube"]["xy_m"])?.try_into().ok()?;
            Some([x, y, source["cube"]["yaw_rad"].as_f64()?])
        }),
    }
}
