//! `fairgrasp fk`: flange and TCP poses for given joint angles.

use std::process::ExitCode;

use clap::Args;
use fairgrasp_kinematics::{EndFrame, manipulability, min_singular_value};
use serde_json::json;

use super::args::{ModelArg, OutputArgs, fmt_joints, fmt3, joints_from, print_json};

#[derive(Args, Debug)]
pub struct FkArgs {
    /// Arm model.
    #[arg(long, value_enum, default_value = "fr3", conflicts_with = "urdf")]
    model: ModelArg,
    /// Any serial arm's URDF instead of the built-in model: the pose of the chain's tip.
    #[arg(long, value_name = "FILE")]
    urdf: Option<std::path::PathBuf>,
    /// The chain's tip link with --urdf (default: the URDF's only leaf).
    #[arg(long, value_name = "LINK", requires = "urdf")]
    tip: Option<String>,
    /// Joint values: q1 … q6 of the FR3/FR5 (radians, or degrees with --deg); with --urdf, one
    /// per movable joint of the chain, as many as it has (revolute: radians or --deg;
    /// prismatic: metres). Flags may follow the list.
    #[arg(
        long,
        num_args = 1..,
        required = true,
        allow_hyphen_values = true, value_parser = crate::cli::args::finite_number,
        value_name = "Q"
    )]
    joints: Vec<f64>,
    #[command(flatten)]
    out: OutputArgs,
}

pub fn run(a: &FkArgs) -> anyhow::Result<ExitCode> {
    if let Some(path) = &a.urdf {
        return super::chain::run_fk(path, a.tip.as_deref(), &a.joints, &a.out);
    }
    let model = a.model.model();
    let q = joints_from(&a.joints, &a.out, "--joints")?;
    let flange = model.fk_flange(&q);
    let tcp = model.fk_tcp(&q);
    let jac = model.jacobian(&q, EndFrame::Tcp);
    let in_limits = model.in_limits(&q, 0.0);
    if a.out.json {
        print_json(&json!({
            "model": model.kind.name(),
            "joints": q,
            "in_limits": in_limits,
            "flange": flange.record(),
            "tcp": tcp.record(),
            "tcp_manipulability": manipulability(&jac),
            "tcp_min_singular_value": min_singular_value(&jac),
        }));
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{} forward kinematics, poses in base_link",
        model.kind.name().to_uppercase()
    );
    println!("  joints       {}", fmt_joints(&q));
    if let Some((i, v)) = model.first_limit_violation(&q) {
        let spec = model.joints[i];
        println!(
            "  warning      {} = {:.4} rad is outside its limits [{:.4}, {:.4}]",
            spec.name, v, spec.lower, spec.upper
        );
    }
    for (name, pose) in [("tool0", flange), ("tcp", tcp)] {
        let q = pose.quat_xyzw();
        let rpy = pose.rpy().map(f64::to_degrees);
        println!("  {name:<6} xyz  {} m", fmt3(pose.xyz()));
        println!("         rpy  {} deg (URDF: fixed x, y, z)", fmt3(rpy));
        println!(
            "         quat ({:.5}, {:.5}, {:.5}, {:.5}) [x, y, z, w]",
            q[0], q[1], q[2], q[3]
        );
    }
    println!(
        "  tcp Jacobian manipulability {:.4e}, smallest singular value {:.4e} (0 = singular)",
        manipulability(&jac),
        min_singular_value(&jac)
    );
    Ok(ExitCode::SUCCESS)
}
