//! `fairgrasp fk --urdf FILE` and `fairgrasp ik --urdf FILE`: forward and inverse kinematics of
//! any serial chain of a URDF (N movable joints, `--tip LINK` where the chain does not end at
//! the URDF's only leaf), by [`fairgrasp_kinematics::chain_ik`].

use std::path::Path;
use std::process::ExitCode;

use fairgrasp_kinematics::chain_ik::{ChainIk, ChainIkOptions};
use fairgrasp_kinematics::{JointKind, Pose, UrdfRobot};
use serde_json::json;

use super::args::{OutputArgs, UsageError, fmt3, print_json};

/// The chain of the URDF at `path` to `tip`.
fn chain(path: &Path, tip: Option<&str>) -> anyhow::Result<ChainIk> {
    Ok(ChainIk::new(&UrdfRobot::from_file(path)?, tip)?)
}

/// Joint values from the command line for `ik`'s chain: as many as it has movable joints;
/// revolute angles per `--deg`, prismatic offsets in metres.
fn values(ik: &ChainIk, given: &[f64], out: &OutputArgs, flag: &str) -> anyhow::Result<Vec<f64>> {
    if given.len() != ik.dof() {
        return Err(UsageError(format!(
            "{flag}: the chain to `{}` has {} movable joints ({}), got {} values",
            ik.chain.tip,
            ik.dof(),
            ik.names.join(", "),
            given.len()
        ))
        .into());
    }
    let kinds = ik.chain.joints.iter().filter(|j| j.kind.is_single_axis());
    Ok(given
        .iter()
        .zip(kinds)
        .map(|(&v, j)| {
            if j.kind == JointKind::Prismatic {
                v
            } else {
                out.angle(v)
            }
        })
        .collect())
}

fn pose_lines(name: &str, pose: &Pose) {
    println!("  {name:<10} xyz  {} m", fmt3(pose.xyz()));
    println!(
        "             rpy  {} deg (URDF: fixed x, y, z)",
        fmt3(pose.rpy().map(f64::to_degrees))
    );
}

pub fn run_fk(
    path: &Path,
    tip: Option<&str>,
    joints: &[f64],
    out: &OutputArgs,
) -> anyhow::Result<ExitCode> {
    let ik = chain(path, tip)?;
    let q = values(&ik, joints, out, "--joints")?;
    let pose = ik.chain.fk(&q);
    let outside: Vec<&str> = (0..ik.dof())
        .filter(|&i| q[i] < ik.lower[i] || q[i] > ik.upper[i])
        .map(|i| ik.names[i].as_str())
        .collect();
    if out.json {
        print_json(&json!({
            "urdf": path, "tip": ik.chain.tip, "joint_names": ik.names, "joints": q,
            "in_limits": outside.is_empty(), "pose": pose.record(),
        }));
        return Ok(ExitCode::SUCCESS);
    }
    println!(
        "{}: forward kinematics to `{}`, {} joints",
        path.display(),
        ik.chain.tip,
        ik.dof()
    );
    pose_lines(&ik.chain.tip, &pose);
    if !outside.is_empty() {
        println!("  warning    outside their limits: {}", outside.join(", "));
    }
    Ok(ExitCode::SUCCESS)
}

pub struct ChainIkRequest<'a> {
    pub path: &'a Path,
    pub tip: Option<&'a str>,
    pub pose: Pose,
    pub current: Option<&'a [f64]>,
    pub seed: u64,
}

pub fn run_ik(r: &ChainIkRequest<'_>, out: &OutputArgs) -> anyhow::Result<ExitCode> {
    let ik = chain(r.path, r.tip)?;
    let start = match r.current {
        Some(values_given) => values(&ik, values_given, out, "--current")?,
        None => (0..ik.dof())
            .map(|i| 0f64.clamp(ik.lower[i], ik.upper[i]))
            .collect(),
    };
    let options = ChainIkOptions {
        seed: r.seed,
        ..ChainIkOptions::default()
    };
    let answer = ik.solve(&r.pose, &start, &options);
    if out.json {
        let mut doc = json!({
            "urdf": r.path, "tip": ik.chain.tip, "joint_names": ik.names, "target": r.pose.record(),
            "current": start,
        });
        doc["solution"] = match &answer {
            Ok(s) => {
                json!({"converged": true, "joints": s.joints, "fk_error_m": s.position_error_m,
                "fk_error_rad": s.orientation_error_rad, "iterations": s.iterations, "attempts": s.attempts})
            }
            Err(e) => json!({"converged": false, "error": e.to_string()}),
        };
        print_json(&doc);
    } else {
        println!(
            "{}: inverse kinematics of `{}`, {} joints",
            r.path.display(),
            ik.chain.tip,
            ik.dof()
        );
        pose_lines("target", &r.pose);
        match &answer {
            Ok(s) => {
                let shown: Vec<String> = (0..ik.dof())
                    .map(|i| format!("{} {:.4}", ik.names[i], s.joints[i]))
                    .collect();
                println!("  joints     {} (rad or m)", shown.join(", "));
                println!(
                    "  error      {:.1e} m / {:.1e} rad, {} QP steps, {} attempt(s)",
                    s.position_error_m, s.orientation_error_rad, s.iterations, s.attempts
                );
            }
            Err(e) => println!("  no solution: {e}"),
        }
    }
    Ok(if answer.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}
