//! Argument pieces shared by several subcommands, and number formatting.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use clap::{Args, ValueEnum};
use fairgrasp_kinematics::{ArmKind, ArmModel, EndFrame, Pose};

/// The arm model to use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ModelArg {
    /// FAIRINO FR3 (0.622 m reach) with the parallel gripper.
    Fr3,
    /// FAIRINO FR5 (longer links; FR3 limits).
    Fr5,
}

impl ModelArg {
    pub fn model(self) -> ArmModel {
        match self {
            ModelArg::Fr3 => ArmKind::Fr3.model(),
            ModelArg::Fr5 => ArmKind::Fr5.model(),
        }
    }
}

/// A frame of the end of the arm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FrameArg {
    /// The flange (DH frame 6).
    Tool0,
    /// The tool centre point between the finger pads.
    Tcp,
}

impl From<FrameArg> for EndFrame {
    fn from(f: FrameArg) -> Self {
        match f {
            FrameArg::Tool0 => EndFrame::Flange,
            FrameArg::Tcp => EndFrame::Tcp,
        }
    }
}

/// Output switches common to all subcommands.
#[derive(Args, Debug, Clone, Copy)]
pub struct OutputArgs {
    /// Angles given on the command line are in degrees (output JSON stays in radians).
    #[arg(long)]
    pub deg: bool,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

impl OutputArgs {
    /// Converts a command-line angle to radians.
    pub fn angle(&self, value: f64) -> f64 {
        if self.deg { value.to_radians() } else { value }
    }
}

/// A command line that cannot mean anything, found after parsing (a list of joint values of
/// the wrong length for the arm): it exits with code 2, as clap's own usage errors do.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// Six joint angles from the command line, checked finite and converted to radians.
pub fn joints_from(values: &[f64], out: &OutputArgs, flag: &str) -> anyhow::Result<[f64; 6]> {
    let q: [f64; 6] = values.try_into().map_err(|_| {
        UsageError(format!(
            "{flag} takes 6 joint angles (q1 … q6 of the FR3/FR5), got {}; another arm's chain \
             takes one per joint with --urdf FILE",
            values.len()
        ))
    })?;
    if let Some(i) = q.iter().position(|v| !v.is_finite()) {
        bail!("{flag}: joint j{} is {}, not a finite angle", i + 1, q[i]);
    }
    Ok(q.map(|v| out.angle(v)))
}

/// A pose from `x y z roll pitch yaw` (metres; angles per `--deg`).
pub fn pose_from(values: &[f64], out: &OutputArgs, flag: &str) -> anyhow::Result<Pose> {
    let [x, y, z, r, p, w]: [f64; 6] = values.try_into().map_err(|_| {
        anyhow::anyhow!(
            "{flag} takes x y z roll pitch yaw, got {} numbers",
            values.len()
        )
    })?;
    Pose::try_from_xyz_rpy([x, y, z], [out.angle(r), out.angle(p), out.angle(w)])
        .with_context(|| flag.to_string())
}

/// `(a, b, c)` with 4 decimals.
pub fn fmt3(v: [f64; 3]) -> String {
    // Adding 0.0 turns -0.0 into 0.0, so rounding noise does not print as "-0.0000".
    let v = v.map(|x| if x.abs() < 5e-5 { 0.0 } else { x + 0.0 });
    format!("({:8.4}, {:8.4}, {:8.4})", v[0], v[1], v[2])
}

/// Joint angles in radians and degrees.
pub fn fmt_joints(q: &[f64; 6]) -> String {
    let rad: Vec<String> = q.iter().map(|v| format!("{v:8.4}")).collect();
    let deg: Vec<String> = q
        .iter()
        .map(|v| format!("{:7.2}", v.to_degrees()))
        .collect();
    format!("[{}] rad  [{}] deg", rad.join(" "), deg.join(" "))
}

/// Prints a serialisable value as one line of JSON.
pub fn print_json(value: &serde_json::Value) {
    println!("{value}");
}

/// The largest magnitude a number on the command line may have (lengths in metres, angles in
/// radians or degrees): beyond it squares and products of poses overflow to infinity.
pub const MAX_CLI_NUMBER: f64 = 1e6;

/// Parses a finite number within ±[`MAX_CLI_NUMBER`] (clap value parser); exponent forms such as
/// `-1e-12` are numbers too.
pub fn finite_number(text: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| {
        if text.starts_with("--") {
            // A flag after a list of any length written `--joints=…` is read as a value.
            format!("{text:?} is not a number: put flags before a list of numbers, not after it")
        } else {
            format!("{text:?} is not a number")
        }
    })?;
    if !value.is_finite() || value.abs() > MAX_CLI_NUMBER {
        return Err(format!(
            "{text}: must be a finite number within ±{MAX_CLI_NUMBER:e}"
        ));
    }
    Ok(value)
}

/// Parses a positive, finite number of seconds (clap value parser).
pub fn positive_seconds(text: &str) -> Result<f64, String> {
    let value = finite_number(text)?;
    if value <= 0.0 {
        return Err(format!("{text}: must be a positive number of seconds"));
    }
    Ok(value)
}

/// The most scenarios one command runs, records or checks \[scenarios\]: 10⁶ (`eval` and
/// `baseline` had this cap first; `compare` runs it for every method and preset). Every count of episodes, scenarios or resets on the command line is bounded by it where it is
/// parsed, and every index into a scenario set by it minus one.
pub const MAX_EPISODES: u32 = 1_000_000;

/// The largest seed on the command line: 2⁵³ − 1, the largest integer every reader of the
/// files a seed is written into keeps exact (JavaScript's numbers in replay.html, TOML's i64 in
/// a run's config.toml). Larger seeds would be stored as another seed.
pub const MAX_SEED: u64 = (1 << 53) - 1;

/// Parses a whole number within `range` (clap value parser); the message gives the range, as
/// clap's own range checks do (`-1 is not in 0..=1000000`), a negative number included.
pub fn whole_number_in(text: &str, range: RangeInclusive<u64>) -> Result<u64, String> {
    let (lo, hi) = (range.start(), range.end());
    let t = text.trim();
    let digits = t.strip_prefix(['-', '+']).unwrap_or(t);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("{text:?} is not a whole number in {lo}..={hi}"));
    }
    match t.parse::<u64>() {
        Ok(n) if range.contains(&n) => Ok(n),
        _ => Err(format!("{t} is not in {lo}..={hi}")),
    }
}

/// Parses a count of episodes (scenarios), 1–[`MAX_EPISODES`] (clap value parser).
pub fn episode_count(text: &str) -> Result<u32, String> {
    whole_number_in(text, 1..=u64::from(MAX_EPISODES)).map(|n| n as u32)
}

/// Parses a count of scenarios that may be 0 (none), 0–[`MAX_EPISODES`] (clap value parser).
pub fn scenario_count(text: &str) -> Result<usize, String> {
    whole_number_in(text, 0..=u64::from(MAX_EPISODES)).map(|n| n as usize)
}

/// Parses an index into a scenario set, 0–[`MAX_EPISODES`] − 1 (clap value parser).
pub fn scenario_index(text: &str) -> Result<usize, String> {
    whole_number_in(text, 0..=u64::from(MAX_EPISODES) - 1).map(|n| n as usize)
}

/// The current name of the preset `name` (a renamed preset's old name gives the new one, with
/// a one-line note on stderr); any other name or `.toml` path as it is.
pub fn preset_name(name: &str) -> String {
    if let Some(note) = fairgrasp_env::config::presets::rename_note(name) {
        eprintln!("note: {note}");
    }
    fairgrasp_env::config::presets::current_name(name)
        .0
        .to_string()
}

/// Parses a `--preset` (clap value parser): [`preset_name`], so every output carries the
/// current name.
pub fn preset(text: &str) -> Result<String, String> {
    Ok(preset_name(text))
}

/// Parses a seed, 0–[`MAX_SEED`] (clap value parser).
pub fn seed(text: &str) -> Result<u64, String> {
    whole_number_in(text, 0..=MAX_SEED)
}

/// Parses a worker-thread count, 1–256 (clap value parser).
pub fn thread_count(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(n) if (1..=256).contains(&n) => Ok(n),
        _ => Err(format!("{text}: give a whole number of threads in 1..=256")),
    }
}

/// The checkpoint folder a `--policy` names, resolved as every command resolves it
/// ([`fairgrasp_policy::shipped::checkpoint_folder`]: a shipped policy's name, a policy folder, a
/// checkpoint folder or a run folder). A folder whose `meta.json` exists but is not a regular
/// file is returned as it is, so that loading it says what is wrong with it.
pub fn policy_folder(given: &str) -> anyhow::Result<PathBuf> {
    match fairgrasp_policy::shipped::checkpoint_folder(given) {
        Ok(dir) => Ok(dir),
        Err(_) if Path::new(given).join("meta.json").exists() => Ok(PathBuf::from(given)),
        Err(why) => bail!("--policy {why}"),
    }
}
