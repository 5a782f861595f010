//! `fairgrasp frames`: the seed recipe's frame sanity checks, with numbers.

use std::process::ExitCode;

use clap::Args;
use fairgrasp_kinematics::fairino::FR3_ZERO_FLANGE_XYZ;
use fairgrasp_kinematics::pose::naive_world_to_base;
use fairgrasp_kinematics::{ArmKind, world_to_base};
use serde_json::json;

use super::args::{ModelArg, OutputArgs, fmt3, pose_from, print_json};

#[derive(Args, Debug)]
pub struct FramesArgs {
    /// Arm model.
    #[arg(long, value_enum, default_value = "fr3")]
    model: ModelArg,
    /// base_link's pose in the world: x y z [m] roll pitch yaw (radians or --deg).
    #[arg(long, num_args = 6, allow_hyphen_values = true, value_parser = crate::cli::args::finite_number,
          default_values_t = [0.2, -0.1, 0.62, 0.0, 0.0, std::f64::consts::FRAC_PI_2],
          value_names = ["X", "Y", "Z", "ROLL", "PITCH", "YAW"])]
    base: Vec<f64>,
    /// A point in the world [m], e.g. the cube's centre.
    #[arg(long, num_args = 3, allow_hyphen_values = true, value_parser = crate::cli::args::finite_number, default_values_t = [0.6, 0.1, 0.645],
          value_names = ["X", "Y", "Z"])]
    point: Vec<f64>,
    #[command(flatten)]
    out: OutputArgs,
}

pub fn run(a: &FramesArgs) -> anyhow::Result<ExitCode> {
    let model = a.model.model();
    let flange = model.fk_flange(&[0.0; 6]);
    let tcp = model.fk_tcp(&[0.0; 6]);
    let base = pose_from(&a.base, &a.out, "--base")?;
    let point: [f64; 3] = a.point.as_slice().try_into()?;
    if point.iter().any(|v| !v.is_finite()) {
        anyhow::bail!("--point {point:?} is not finite");
    }
    let right = world_to_base(&base, point);
    let naive = naive_world_to_base(&base, point);
    let gap = (0..3)
        .map(|i| (right[i] - naive[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    let check = (model.kind == ArmKind::Fr3).then(|| {
        (0..3)
            .map(|i| (flange.xyz()[i] - FR3_ZERO_FLANGE_XYZ[i]).abs())
            .fold(0.0, f64::max)
    });

    if a.out.json {
        print_json(&json!({
            "model": model.kind.name(),
            "zero_pose": {"flange": flange.record(), "tcp": tcp.record(),
                          "flange_published_xyz": check.map(|_| FR3_ZERO_FLANGE_XYZ),
                          "flange_error_m": check},
            "base_in_world": base.record(),
            "point_world": point,
            "point_base": right,
            "point_base_naive": naive,
            "naive_error_m": gap,
        }));
        return Ok(ExitCode::SUCCESS);
    }
    let name = model.kind.name().to_uppercase();
    println!("Zero pose ({name}, all joints 0), in base_link:");
    println!("  tool0 xyz {} m", fmt3(flange.xyz()));
    let r = flange.rotation_rows();
    println!(
        "        rotation rows {:?} {:?} {:?}",
        r[0].map(round),
        r[1].map(round),
        r[2].map(round)
    );
    if let Some(err) = check {
        let verdict = if err < 1e-9 {
            "matches"
        } else {
            "DIFFERS from"
        };
        println!(
            "        {verdict} FAIRINO's published {} (error {err:.1e} m)",
            fmt3(FR3_ZERO_FLANGE_XYZ)
        );
    }
    println!(
        "  tcp   xyz {} m ({} m along the flange z axis)",
        fmt3(tcp.xyz()),
        model.gripper.tcp_offset
    );
    println!();
    println!("A world point in the arm's base frame:");
    println!(
        "  base_link in world  xyz {} m, rpy {} deg",
        fmt3(base.xyz()),
        fmt3(base.rpy().map(f64::to_degrees))
    );
    println!("  point in world          {} m", fmt3(point));
    println!(
        "  right: T_world_base⁻¹·p {} m  (invertTransform + multiplyTransforms)",
        fmt3(right)
    );
    println!(
        "  wrong: p − t_world_base {} m  (subtracting positions)",
        fmt3(naive)
    );
    println!(
        "  the wrong way is off by {gap:.4} m{}",
        if gap < 1e-12 {
            " (the base is not rotated)"
        } else {
            ""
        }
    );
    Ok(ExitCode::SUCCESS)
}

fn round(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}
