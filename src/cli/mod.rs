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
mod tune;
mod wrench_probe;

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
    /// Tune a hand-written control's parameters on training scenarios with CMA-ES, within a
    /// budget of env steps: every trial as CSV, the best as a preset fragment (resumable).
    Tune(tune::TuneArgs),
    /// What the six-axis wrist sensor tells at a place cycle's first touch (the wall the cube
    /// rests on, the sign of its tilt in the grip), checked against the truth on training
    /// scenarios before any control uses it.
    WrenchProbe(wrench_probe::WrenchProbeArgs),
    /// Benchmarks: `bench env` measures environment steps per second and reset times.
    Bench(bench::BenchArgs),
}

impl Cli {
    /// Parses `argv` (the program's name first). A list of numbers of any length (`fk
    /// --joints`, `ik --current`: as many values as the `--urdf` chain has joints) takes the
    /// words after it up to the next flag: a word that starts with `-` ends the list unless it
    /// is a number (`-1e-12`, `-0.5`), so flags may follow the list as they follow any other.
    pub fn try_parse_from_args(argv: Vec<OsString>) -> Result<Cli, clap::Error> {
        let mut command = negative_numbers_are_values(Cli::command());
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

/// `command` with every flag that takes a value, in every subcommand, taking a negative number
/// as its value: `--noise -0.5` or `--episodes -5` is then refused by the flag's range, naming
/// the flag and the range, where clap would call `-0` an unexpected argument.
fn negative_numbers_are_values(command: clap::Command) -> clap::Command {
    command
        .mut_args(|a| {
            if a.get_action().takes_values() {
                a.allow_negative_numbers(true)
            } else {
                a
            }
        })
        .mut_subcommands(negative_numbers_are_values)
}

/// Is `word` a value of a list of numbers (not a flag)? A word that does not start with `-`, or
/// a negative number; a word that is not a number is a value too, which the list's parser then
/// refuses naming it.
fn is_list_value(word: &str) -> bool {
    !word.starts_with('-') || word.parse::<f64>().is_ok()
}

/// Runs one subcommand; `Ok` carries the exit code (non-zero when the answer is "no solution").
impl Cli {
    /// Whether the command writes files (`main` then lets it finish them when nobody reads its
    /// stdout).
    pub fn writes_files(&self) -> bool {
        match &self.command {
            Command::Joints(_)
            | Command::Fk(_)
            | Command::Ik(_)
            | Command::Frames(_)
            | Command::Scene(_)
            | Command::Playback(_)
            | Command::Bench(_) => false,
            Command::WrenchProbe(_) => true,
            Command::Eval(a) => a.writes_files(),
            // `--record DIR` (a field private to the baseline module) may write files.
            Command::Baseline(_)
            | Command::Calibrate(_)
            | Command::Train(_)
            | Command::Compare(_)
            | Command::Plot(_)
            | Command::Report(_)
            | Command::Export(_)
            | Command::Replay(_)
            | Command::Tune(_) => true,
        }
    }
}

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
        Command::Tune(a) => tune::run(&a),
        Command::WrenchProbe(a) => wrench_probe::run(&a),
    }
}

#[cfg(test)]
mod tests {
    use std::any::TypeId;

    use clap::CommandFactory;
    use clap::error::ErrorKind;

    use super::Cli;

    /// The subcommand path, `--long` name and help text of every flag that parses an integer.
    fn integer_flags(
        command: &clap::Command,
        path: &[String],
        out: &mut Vec<(Vec<String>, String, String)>,
    ) {
        let integers = [
            TypeId::of::<u8>(),
            TypeId::of::<u16>(),
            TypeId::of::<u32>(),
            TypeId::of::<u64>(),
            TypeId::of::<usize>(),
        ];
        for arg in command.get_arguments() {
            let id = arg.get_value_parser().type_id();
            if let Some(long) = arg.get_long()
                && integers.iter().any(|t| id == *t)
            {
                let help = arg
                    .get_long_help()
                    .or(arg.get_help())
                    .map(|h| h.to_string())
                    .unwrap_or_default();
                out.push((path.to_vec(), format!("--{long}"), help));
            }
        }
        for sub in command.get_subcommands() {
            let mut deeper = path.to_vec();
            deeper.push(sub.get_name().to_string());
            integer_flags(sub, &deeper, out);
        }
    }

    /// The first `A–B` of whole numbers in `help`.
    fn stated_range(help: &str) -> Option<(u64, u64)> {
        help.match_indices('–').find_map(|(at, dash)| {
            let before = &help[..at];
            let start = before
                .rfind(|c: char| !c.is_ascii_digit())
                .map_or(0, |i| i + 1);
            let after = &help[at + dash.len()..];
            let end = after
                .find(|c: char| !c.is_ascii_digit())
                .unwrap_or(after.len());
            Some((before[start..].parse().ok()?, after[..end].parse().ok()?))
        })
    }

    /// Parses `path flag value`: `Err` with the message when the value is refused by its range
    /// (a missing required flag, or any other complaint, means the value itself was taken).
    fn value_refused(path: &[String], flag: &str, value: &str) -> Result<(), String> {
        let mut argv: Vec<std::ffi::OsString> = vec!["fairgrasp".into()];
        argv.extend(path.iter().map(Into::into));
        argv.extend([flag.into(), value.into()]);
        match Cli::try_parse_from_args(argv) {
            Err(e) if e.kind() == ErrorKind::ValueValidation => Err(e.render().to_string()),
            _ => Ok(()),
        }
    }

    /// Every count and seed on the command line is bounded where it is parsed, and its `--help`
    /// says the bound: the help states `A–B`, B is taken, B + 1, A − 1 (a negative number when
    /// A = 0, parsed as a number, not a flag) and 2⁶⁴ − 1 are refused by a message naming the
    /// flag and the range `A..=B`. `compare --episodes 4294967295` (hours) and `scene --seeds 18446744073709551615`
    /// (never returns) used to be taken.
    #[test]
    fn every_integer_flag_states_its_range_and_refuses_values_outside_it() {
        let mut flags = Vec::new();
        integer_flags(&Cli::command(), &[], &mut flags);
        assert!(flags.len() >= 20, "{} integer flags found", flags.len());
        for (path, flag, help) in &flags {
            let at = format!("{} {flag}", path.join(" "));
            let (lo, hi) = stated_range(help)
                .unwrap_or_else(|| panic!("{at}: its help states no range A–B: {help:?}"));
            assert!(lo <= hi, "{at}: {lo}–{hi}");
            assert_eq!(
                value_refused(path, flag, &hi.to_string()),
                Ok(()),
                "{at}: the help's upper bound {hi} is refused"
            );
            let below = if lo == 0 {
                "-1".to_string()
            } else {
                (lo - 1).to_string()
            };
            for bad in [(hi + 1).to_string(), below, u64::MAX.to_string()] {
                let message = value_refused(path, flag, &bad)
                    .expect_err(&format!("{at} {bad}: taken, outside {lo}–{hi}"));
                assert!(
                    message.contains(flag.as_str()) && message.contains(&format!("{lo}..={hi}")),
                    "{at} {bad}: {message}"
                );
            }
        }
    }
}
