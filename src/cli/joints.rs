//! `fairgrasp joints`: the joint table of a URDF.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use fairgrasp_kinematics::urdf::JointKind;
use fairgrasp_kinematics::{FR3_URDF, UrdfRobot};
use serde_json::json;

use super::args::{OutputArgs, print_json};

#[derive(Args, Debug)]
pub struct JointsArgs {
    /// URDF file to read (default: the built-in assets/fr3.urdf).
    #[arg(long, value_name = "PATH")]
    urdf: Option<PathBuf>,
    /// Tip link of the serial chain to report (default: tcp if present, else the only leaf).
    #[arg(long, value_name = "LINK")]
    tip: Option<String>,
    #[command(flatten)]
    out: OutputArgs,
}

pub fn run(a: &JointsArgs) -> anyhow::Result<ExitCode> {
    let robot = match &a.urdf {
        Some(path) => UrdfRobot::from_file(path)?,
        None => UrdfRobot::from_str_named(FR3_URDF, "assets/fr3.urdf (built in)")?,
    };
    let default_tip = robot.links.iter().any(|l| l == "tcp").then_some("tcp");
    let chain = robot.chain(a.tip.as_deref().or(default_tip));
    if a.tip.is_some() {
        // An explicitly requested tip must exist and be reachable.
        if let Err(e) = &chain {
            anyhow::bail!("{e}");
        }
    }
    if a.out.json {
        let mut out = json!({"file": robot.file, "robot": robot.name, "root": robot.root, "joints": robot.joints});
        match &chain {
            Ok(c) => out["chain"] = json!({"tip": c.tip, "movable_joints": c.joint_names()}),
            Err(e) => out["chain_error"] = json!(e.to_string()),
        }
        print_json(&out);
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{} — robot '{}', root link '{}', {} joints",
        robot.file,
        robot.name,
        robot.root,
        robot.joints.len()
    );
    let unit = if a.out.deg { "deg" } else { "rad" };
    println!(
        "{:>3}  {:<24} {:<10} {:<34} {:>10} {:>10} {:>9} {:>8}",
        "#", "joint", "type", "parent -> child", "lower", "upper", "velocity", "effort"
    );
    for (i, j) in robot.joints.iter().enumerate() {
        let angular = matches!(j.kind, JointKind::Revolute | JointKind::Continuous);
        let show = |v: f64| {
            if angular && a.out.deg {
                v.to_degrees()
            } else {
                v
            }
        };
        let (lower, upper) = match j.limits {
            Some([lo, hi]) => (format!("{:10.4}", show(lo)), format!("{:10.4}", show(hi))),
            None => (format!("{:>10}", "-"), format!("{:>10}", "-")),
        };
        let links = format!("{} -> {}", j.parent, j.child);
        println!(
            "{i:>3}  {:<24} {:<10} {links:<34} {lower} {upper} {:>9.3} {:>8.1}",
            j.name,
            j.kind.name(),
            j.max_velocity,
            j.max_effort
        );
    }
    println!(
        "limits in {unit} (revolute) or m (prismatic); velocity in rad/s or m/s; effort in N·m or N"
    );
    match chain {
        Ok(c) => println!(
            "serial chain {} -> {}: {} movable joints ({})",
            robot.root,
            c.tip,
            c.dof(),
            c.joint_names().join(", ")
        ),
        Err(e) => println!("no single serial chain: {e}"),
    }
    Ok(ExitCode::SUCCESS)
}
