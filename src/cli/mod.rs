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

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

pub use args::UsageError;

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

impl Cli {
    /// Parses `argv` (the program's name first). A list of numbers of any length (`fk
    /// --joints`, `ik --current`: as many values as the `--urdf` chain has joints) takes the
    /// words after it up to the next flag: a word that starts with `-` ends the list unless it
    /// is a number (`-1e-12`, `-0.5`), so flags may follow the list as they follow any other.
    pub fn try_parse_from_args(argv: Vec<OsString>) -> Result<Cli, clap::Error> {
        let mut command = Cli::command();
        let subcommand = argv
            .iter()
            .skip(1)
            .filter_map(|a| a.to_str())
            .find(|a| !a.starts_with('-'));
        if let Some(name) = subcommand.filter(|n| command.find_subcommand(n).is_some()) {
            let name = name.to_string();
            let lists: Vec<(clap::Id, String)> = command
                .find_subcommand(&name)
                .expect("found above")
                .get_arguments()
                .filter(|a| {
                    a.is_allow_hyphen_values_set()
                        && a.get_num_args()
                            .is_some_and(|n| n.max_values() == usize::MAX)
                })
                .filter_map(|a| Some((a.get_id().clone(), format!("--{}", a.get_long()?))))
                .collect();
            for (id, flag) in lists {
                let Some(at) = argv.iter().position(|a| a.to_str() == Some(flag.as_str())) else {
                    continue;
                };
                let values = argv[at + 1..]
                    .iter()
                    .take_while(|a| a.to_str().is_some_and(is_list_value))
                    .count();
                if values > 0 {
                    command = command
                        .mut_subcommand(&name, |sub| sub.mut_arg(id, |a| a.num_args(values)));
                }
            }
        }
        let matches = command.try_get_matches_from(argv)?;
        Cli::from_arg_matches(&matches)
    }
}

/// Is `word` a value of a list of numbers (not a flag)? A word that does not start with `-`, or
/// a negative number; a word that is not a number is a value too, which the list's parser then
/// refuses naming it.
fn is_list_value(word: &str) -> bool {
    !word.starts_with('-') || word.parse::<f64>().is_ok()
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
