//! Subcommands and their arguments.

mod args;
mod baseline;
mod bench;
#[cfg(feature = "train")]
mod bench_ppo;
mod calibrate;
mod chain;
mod compare;
mod eval;
mod export;
mod fk;
mod frames;
mod ik;
mod joints;
mod measurements;
mod playback;
mod progress;
mod replay;
mod report;
mod scene;
mod soak;
mod squeeze_chart;
mod train;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// fairgrasp: kinematics, grasping and residual PPO for the FAIRINO FR3 cobot.
///
/// Frames follow ROS: world, base_link, tool0 (the flange) and tcp (between the finger pads,
/// 0.14 m past tool0). Lengths are metres; angles on the command line are radians unless --deg.
#[derive(Parser, Debug)]
#[command(name = "fairgrasp", version, about, long_about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// List a URDF's joints: names, types, parent and child links, limits (the seed's joint list).
    Joints(joints::JointsArgs),
    /// Forward kinematics: flange (tool0) and TCP poses in base_link for given joint angles.
    Fk(fk::FkArgs),
    /// Inverse kinematics: every closed-form branch for a pose, optionally the QP solver too.
    Ik(ik::IkArgs),
    /// Frame sanity checks: the zero pose, and a world point expressed in a rotated base frame.
    Frames(frames::FramesArgs),
    /// Calibrate a real cell from measurements: the base's mount from touched points, a fixed
    /// camera's pose from robot and marker poses (hand-eye).
    Calibrate(calibrate::CalibrateArgs),
    /// The scene's numbers and every contact right after a reset: collisions, ignored pairs.
    Scene(scene::SceneArgs),
    /// The scripted grasp baseline on a preset's seeded scenario set: success rate and failures.
    Baseline(baseline::BaselineArgs),
    /// Train a PPO agent (residual on the baseline, or pure) from a TOML config (needs a build
    /// with the `train` feature: `cargo run --release --features train -- train …`).
    Train(train::TrainArgs),
    /// Evaluate a trained agent (default: the shipped residual policy) on a preset.
    Eval(eval::EvalArgs),
    /// The baseline and learned policies on identical scenario sets: table, CSV/JSON, charts,
    /// replays, report.md and report.ipynb in one folder (the main job).
    Compare(compare::CompareArgs),
    /// Learning curves of run folders; episode charts and GIF replays of recorded episodes.
    Plot(report::PlotArgs),
    /// report.md and a Jupyter notebook (report.ipynb) from comparison and run folders.
    Report(report::ReportArgs),
    /// One episode (a script or policy on a preset's scenario, or a cube placed by hand) as a
    /// servo stream for a real FR3: resampled to the controller's period, checked against its
    /// limits, written as JSON (the ROS 2 driver's stream_servo_j goal), CSV or .npy.
    Export(export::ExportArgs),
    /// Play an exported stream in the env (the servo arm tracking its samples) and report
    /// whether it still grasps.
    Playback(playback::PlaybackArgs),
    /// An interactive 3D replay (one HTML file, no network) of a scenario run by one or more
    /// policies or scripts.
    Replay(replay::ReplayArgs),
    /// Benchmarks: `bench env` measures environment steps per second and reset times.
    Bench(bench::BenchArgs),
}

/// Runs one subcommand; `Ok` carries the exit code (non-zero when the answer is "no solution").
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Joints(a) => joints::run(&a),
        Command::Fk(a) => fk::run(&a),
        Command::Ik(a) => ik::run(&a),
        Command::Frames(a) => frames::run(&a),
        Command::Calibrate(a) => calibrate::run(&a),
        Command::Bench(a) => bench::run(&a),
        Command::Baseline(a) => baseline::run(&a),
        Command::Train(a) => train::run_train(&a),
        Command::Eval(a) => eval::run_eval(&a),
        Command::Compare(a) => compare::run(&a),
        Command::Scene(a) => scene::run(&a),
        Command::Plot(a) => report::run_plot(&a),
        Command::Report(a) => report::run_report(&a),
        Command::Replay(a) => replay::run(&a),
        Command::Export(a) => export::run(&a),
        Command::Playback(a) => playback::run(&a),
    }
}
