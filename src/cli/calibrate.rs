//! `fairgrasp calibrate`: the base's mount (`points`) and a fixed camera's pose (`hand-eye`)
//! from measurements in a real cell; tables in [`super::measurements`].

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::{Args, Subcommand};
use fairgrasp_env::EnvConfig;
use fairgrasp_kinematics::calibrate::{
    HandEyeOptions, HandEyeSample, PointFit, PointFitOptions, PointPair, fit_eye_to_hand,
    fit_points,
};
use fairgrasp_kinematics::{ArmModel, Pose};
use serde_json::json;

use super::args::{ModelArg, fmt3, print_json};
use super::measurements::{Row, Table};

#[derive(Args, Debug)]
pub struct CalibrateArgs {
    #[command(subcommand)]
    what: CalibrateCommand,
}

#[derive(Subcommand, Debug)]
enum CalibrateCommand {
    /// world ↔ base_link from the TCP touched to known world points (≥ 3, not on one line).
    ///
    /// FILE is a CSV table (`#` comments; every column name ends in its unit: _m, _mm, _deg,
    /// _rad). Columns: world_x, world_y, world_z (the point in the world or table frame) and
    /// either tcp_x, tcp_y, tcp_z (the TCP in base_link, as the controller shows it) or j1 … j6
    /// (joint readings; the TCP is computed by FK, 0.14 m past the flange). Example:
    /// assets/calibration/touches_example.csv.
    ///
    /// Prints the mount (base_link in the world) as the env config's [arm] base_xyz / base_rpy,
    /// the residual of every point and the RMS; refuses fewer than 3 points, collinear points,
    /// units that disagree and a point off by more than --max-residual-mm.
    Points(PointsArgs),
    /// base_link ↔ a camera fixed in the cell (eye-to-hand), from stations of the arm.
    ///
    /// FILE is a CSV table as for `points`, one station per row: the TCP pose in base_link
    /// (tcp_x, tcp_y, tcp_z, tcp_roll, tcp_pitch, tcp_yaw, URDF fixed-axis roll-pitch-yaw) or
    /// the joint readings j1 … j6, and the marker's pose in the camera frame (marker_x …
    /// marker_yaw) as the detector reports it. Solved by Park–Martin's AX = XB over every pair
    /// of stations; prints the camera's pose in base_link, the marker's on the TCP and the
    /// residual of every station. Use ≥ 6 stations that turn the marker about different axes.
    /// Controllers' Euler conventions differ: if unsure, give joint readings.
    HandEye(HandEyeArgs),
}

#[derive(Args, Debug)]
struct PointsArgs {
    /// The measurement table (CSV).
    file: PathBuf,
    /// Arm model for joint readings.
    #[arg(long, value_enum, default_value = "fr3")]
    model: ModelArg,
    /// The largest residual accepted for any point [mm].
    #[arg(long, default_value_t = 5.0, value_parser = residual_mm)]
    max_residual_mm: f64,
    /// Also write the mount as an env config file (a new file: an existing one is never
    /// replaced); use it as `--preset FILE` or copy its [arm] table.
    #[arg(long, value_name = "FILE.toml")]
    out: Option<PathBuf>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Args, Debug)]
struct HandEyeArgs {
    /// The measurement table (CSV).
    file: PathBuf,
    /// Arm model for joint readings.
    #[arg(long, value_enum, default_value = "fr3")]
    model: ModelArg,
    /// The largest position residual accepted for any station [mm].
    #[arg(long, default_value_t = 5.0, value_parser = residual_mm)]
    max_residual_mm: f64,
    /// The largest angle residual accepted for any station [deg].
    #[arg(long, default_value_t = 1.0, value_parser = residual_deg)]
    max_residual_deg: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn residual_mm(text: &str) -> Result<f64, String> {
    match super::args::finite_number(text)? {
        v if v > 0.0 && v <= 1000.0 => Ok(v),
        _ => Err(format!("{text}: give a residual bound in (0, 1000] mm")),
    }
}

fn residual_deg(text: &str) -> Result<f64, String> {
    match super::args::finite_number(text)? {
        v if v > 0.0 && v <= 180.0 => Ok(v),
        _ => Err(format!("{text}: give an angle bound in (0, 180] degrees")),
    }
}

pub fn run(a: &CalibrateArgs) -> anyhow::Result<ExitCode> {
    match &a.what {
        CalibrateCommand::Points(p) => points(p),
        CalibrateCommand::HandEye(h) => hand_eye(h),
    }
}

const JOINTS: [&str; 6] = ["j1", "j2", "j3", "j4", "j5", "j6"];
const TCP_XYZ: [&str; 3] = ["tcp_x", "tcp_y", "tcp_z"];
const TCP_RPY: [&str; 3] = ["tcp_roll", "tcp_pitch", "tcp_yaw"];

/// The TCP's pose in base_link of a row: from joint readings (FK) or from the tcp_ columns.
fn tcp_pose(table: &Table, row: &Row, model: &ArmModel, with_rotation: bool) -> Pose {
    if table.has_all(&JOINTS) {
        model.fk_tcp(&table.values(row, JOINTS))
    } else if with_rotation {
        Pose::from_xyz_rpy(table.values(row, TCP_XYZ), table.values(row, TCP_RPY))
    } else {
        Pose::from_xyz(table.values(row, TCP_XYZ))
    }
}

/// Refuses a table that has neither joint readings nor the TCP columns `tcp`, or both.
fn check_tcp_source(table: &Table, tcp: &[&str]) -> anyhow::Result<&'static str> {
    match (table.has_all(&JOINTS), table.has_all(tcp)) {
        (true, false) => Ok("the TCP from joint readings (FK)"),
        (false, true) => Ok("the TCP as measured"),
        (true, true) => bail!(
            "{}: give joint readings or the TCP's columns, not both",
            table.path
        ),
        (false, false) => bail!(
            "{}: the TCP is missing: give j1 … j6 or {} (each with a unit suffix)",
            table.path,
            tcp.join(", ")
        ),
    }
}

fn points(a: &PointsArgs) -> anyhow::Result<ExitCode> {
    let (table, source) = read_touches(&a.file)?;
    let model = a.model.model();
    let pairs: Vec<PointPair> = table
        .rows
        .iter()
        .map(|r| PointPair {
            world: table.values(r, WORLD_XYZ),
            base: tcp_pose(&table, r, &model, false).xyz(),
        })
        .collect();
    let opts = PointFitOptions {
        max_residual: a.max_residual_mm * 1e-3,
        ..PointFitOptions::default()
    };
    let fit = fit_points(&pairs, &opts).with_context(|| table.path.clone())?;
    let fragment = mount_fragment(&table.path, pairs.len(), &fit);
    // The env decides what a mount may be (tilt, height); ask it rather than repeat its rules.
    let env_check = EnvConfig::from_toml_str(&fragment)
        .err()
        .map(|e| e.to_string());
    if let Some(out) = &a.out {
        if let Some(why) = &env_check {
            bail!(
                "{}: not written: the env refuses this mount: {why}",
                out.display()
            );
        }
        write_new(out, &fragment)?;
    }
    let report = PointsReport {
        table: &table,
        source,
        pairs: &pairs,
        fit: &fit,
        fragment: &fragment,
        env_check: env_check.as_deref(),
        out: a.out.as_deref(),
    };
    if a.json {
        print_json(&report.to_json());
    } else {
        report.print();
    }
    Ok(ExitCode::SUCCESS)
}

/// The world point's columns of a touch table.
const WORLD_XYZ: [&str; 3] = ["world_x", "world_y", "world_z"];

/// Reads the touch table `file` (world points and the TCP, measured or from joint readings),
/// refusing one without the world columns or without exactly one TCP source. Returns the table
/// and how its TCP is known.
fn read_touches(file: &std::path::Path) -> anyhow::Result<(Table, &'static str)> {
    let mut allowed = WORLD_XYZ.to_vec();
    allowed.extend(TCP_XYZ.iter().chain(&JOINTS));
    let table = Table::read(file, &allowed)?;
    if !table.has_all(&WORLD_XYZ) {
        bail!(
            "{}: the columns world_x, world_y and world_z are needed",
            table.path
        );
    }
    let source = check_tcp_source(&table, &TCP_XYZ)?;
    Ok((table, source))
}

/// The mount as an env config file: a comment naming its source (`path`, `points` touches, the
/// RMS \[mm\]) and the \[arm\] table's base_xyz \[m\] and base_rpy \[rad\].
fn mount_fragment(path: &str, points: usize, fit: &PointFit) -> String {
    let mount = fit.base_in_world;
    format!(
        "# The arm's mount, calibrated by `fairgrasp calibrate points` from {} ({} points, RMS {:.2} mm).\n\
         # Use this file as `--preset FILE`, or copy the [arm] table into your env config.\n\
         [arm]\nbase_xyz = [{:.6}, {:.6}, {:.6}]\nbase_rpy = [{:.6}, {:.6}, {:.6}]\n",
        path,
        points,
        fit.rms * 1e3,
        mount.xyz()[0],
        mount.xyz()[1],
        mount.xyz()[2],
        mount.rpy()[0],
        mount.rpy()[1],
        mount.rpy()[2],
    )
}

/// What `calibrate points` found, for printing as text or JSON.
struct PointsReport<'a> {
    table: &'a Table,
    /// How the TCP was known (measured, or FK of joint readings).
    source: &'static str,
    pairs: &'a [PointPair],
    fit: &'a PointFit,
    /// The env config text of the mount ([`mount_fragment`]).
    fragment: &'a str,
    /// Why the env refuses the mount, if it does.
    env_check: Option<&'a str>,
    /// Where the fragment was written (--out).
    out: Option<&'a std::path::Path>,
}

impl PointsReport<'_> {
    /// The angle between the base's z axis and the world's \[rad\].
    fn tilt(&self) -> f64 {
        let up = self.fit.base_in_world.transform_vector([0.0, 0.0, 1.0]);
        up[2].clamp(-1.0, 1.0).acos()
    }

    /// The fit as one JSON object (`--json`).
    fn to_json(&self) -> serde_json::Value {
        let fit = self.fit;
        json!({
            "method": "Kabsch closed form, then Gauss–Newton least squares",
            "file": self.table.path, "tcp": self.source, "points": self.pairs.len(),
            "base_in_world": fit.base_in_world.record(), "tilt_rad": self.tilt(),
            "residuals_m": fit.residuals, "rms_m": fit.rms,
            "closed_form_rms_m": fit.closed_form_rms, "iterations": fit.iterations,
            "scale": fit.scale, "spread_m": fit.spread, "warnings": fit.warnings,
            "env_refuses": self.env_check, "out": self.out.map(|p| p.display().to_string()),
        })
    }

    /// Prints every point's residual \[mm\], the RMS, the mount, warnings and the fragment.
    fn print(&self) {
        let (table, fit) = (self.table, self.fit);
        println!(
            "world ↔ base_link from {} touched points ({}; {}):",
            self.pairs.len(),
            table.path,
            self.source
        );
        println!("  row  line  world point [m]                  residual");
        for (i, ((p, r), row)) in self
            .pairs
            .iter()
            .zip(&fit.residuals)
            .zip(&table.rows)
            .enumerate()
        {
            println!(
                "  {:>3}  {:>4}  {}  {:6.2} mm",
                i + 1,
                row.line,
                fmt3(p.world),
                r * 1e3
            );
        }
        self.print_mount();
        println!("\nFor the env config:\n");
        print!("{}", self.fragment);
        if let Some(out) = self.out {
            println!("\nwritten to {}", out.display());
        }
    }

    /// The fit's quality (RMS \[mm\], steps, scale, spread), the mount (xyz \[m\], rpy and
    /// tilt \[deg\]) and any warnings, the env's refusal among them.
    fn print_mount(&self) {
        let fit = self.fit;
        let mount = fit.base_in_world;
        println!(
            "  RMS {:.2} mm (closed form {:.2} mm; Gauss–Newton steps that lowered it: {}); scale {:.4}; spread off the best line {:.0} mm",
            fit.rms * 1e3,
            fit.closed_form_rms * 1e3,
            fit.iterations,
            fit.scale,
            fit.spread[1] * 1e3
        );
        println!(
            "base_link in the world: xyz {} m, rpy {} deg (tilt from upright {:.2}°)",
            fmt3(mount.xyz()),
            fmt3(mount.rpy().map(f64::to_degrees)),
            self.tilt().to_degrees()
        );
        for w in &fit.warnings {
            println!("warning: {w}");
        }
        if let Some(why) = self.env_check {
            println!("warning: the env refuses this mount: {why}");
        }
    }
}

/// Writes `text` to a new file `path` (atomically); an existing path is refused, never replaced.
fn write_new(path: &std::path::Path, text: &str) -> anyhow::Result<()> {
    if std::fs::symlink_metadata(path).is_ok() {
        bail!(
            "{}: already exists; fairgrasp does not replace it: choose another name or move it away",
            path.display()
        );
    }
    fairgrasp_types::fs::write_atomic(path, text.as_bytes())
        .with_context(|| format!("{}: cannot write it", path.display()))
}

fn hand_eye(a: &HandEyeArgs) -> anyhow::Result<ExitCode> {
    let marker = ["marker_x", "marker_y", "marker_z"];
    let marker_rpy = ["marker_roll", "marker_pitch", "marker_yaw"];
    let mut allowed: Vec<&str> = JOINTS.to_vec();
    allowed.extend(
        TCP_XYZ
            .iter()
            .chain(&TCP_RPY)
            .chain(&marker)
            .chain(&marker_rpy),
    );
    let table = Table::read(&a.file, &allowed)?;
    if !table.has_all(&marker) || !table.has_all(&marker_rpy) {
        bail!(
            "{}: the marker's pose in the camera is needed: marker_x, marker_y, marker_z, marker_roll, marker_pitch, marker_yaw",
            table.path
        );
    }
    let mut tcp = TCP_XYZ.to_vec();
    tcp.extend(TCP_RPY);
    let source = check_tcp_source(&table, &tcp)?;
    let model = a.model.model();
    let samples: Vec<HandEyeSample> = table
        .rows
        .iter()
        .map(|r| HandEyeSample {
            tcp_in_base: tcp_pose(&table, r, &model, true),
            marker_in_camera: Pose::from_xyz_rpy(
                table.values(r, marker),
                table.values(r, marker_rpy),
            ),
        })
        .collect();
    let opts = HandEyeOptions {
        max_position_residual: a.max_residual_mm * 1e-3,
        max_angle_residual: a.max_residual_deg.to_radians(),
        ..HandEyeOptions::default()
    };
    let fit = fit_eye_to_hand(&samples, &opts).with_context(|| table.path.clone())?;
    if a.json {
        print_json(&json!({
            "method": fit.method, "file": table.path, "tcp": source, "stations": samples.len(),
            "camera_in_base": fit.camera_in_base.record(), "marker_in_tcp": fit.marker_in_tcp.record(),
            "position_residuals_m": fit.position_residuals, "angle_residuals_rad": fit.angle_residuals,
            "rms_position_m": fit.rms_position, "rms_angle_rad": fit.rms_angle,
            "motions_used": fit.motions_used,
        }));
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "base_link ↔ camera (eye-to-hand) from {} stations ({}; {source}), {}:",
        samples.len(),
        table.path,
        fit.method
    );
    println!("  row  line  residual");
    for (i, ((p, r), row)) in fit
        .position_residuals
        .iter()
        .zip(&fit.angle_residuals)
        .zip(&table.rows)
        .enumerate()
    {
        println!(
            "  {:>3}  {:>4}  {:6.2} mm  {:5.2}°",
            i + 1,
            row.line,
            p * 1e3,
            r.to_degrees()
        );
    }
    println!(
        "  RMS {:.2} mm, {:.2}° ({} motions turned enough to orient the camera)",
        fit.rms_position * 1e3,
        fit.rms_angle.to_degrees(),
        fit.motions_used
    );
    for (name, pose) in [
        ("camera in base_link", fit.camera_in_base),
        ("marker on the TCP  ", fit.marker_in_tcp),
    ] {
        println!(
            "{name}: xyz {} m, rpy {} deg",
            fmt3(pose.xyz()),
            fmt3(pose.rpy().map(f64::to_degrees))
        );
    }
    Ok(ExitCode::SUCCESS)
}
