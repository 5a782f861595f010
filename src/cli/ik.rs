//! `fairgrasp ik`: every closed-form branch for a pose, and optionally the QP solver.

use std::process::ExitCode;

use clap::Args;
use fairgrasp_kinematics::analytic_ik::joint_distance;
use fairgrasp_kinematics::{
    AnalyticIkOptions, ArmModel, EndFrame, IkError, IkSolution, Pose, QpIkError, QpIkOptions,
    QpIkSolution, nearest_solution,
};
use serde_json::json;

use super::args::{
    FrameArg, ModelArg, OutputArgs, fmt_joints, fmt3, joints_from, pose_from, print_json,
};

#[derive(Args, Debug)]
pub struct IkArgs {
    /// Arm model.
    #[arg(long, value_enum, default_value = "fr3", conflicts_with = "urdf")]
    model: ModelArg,
    /// Any serial arm's URDF instead of the built-in model: the chain IK (damped QP steps
    /// within the joint limits, random restarts) places the chain's tip at --pose, in the
    /// URDF's root frame.
    #[arg(long, value_name = "FILE", conflicts_with = "frame")]
    urdf: Option<std::path::PathBuf>,
    /// The chain's tip link with --urdf (default: the URDF's only leaf).
    #[arg(long, value_name = "LINK", requires = "urdf")]
    tip: Option<String>,
    /// Target pose in base_link: x y z [m] roll pitch yaw (URDF fixed-axis; radians or --deg).
    #[arg(long, num_args = 6, required = true, allow_hyphen_values = true, value_parser = crate::cli::args::finite_number, value_names = ["X", "Y", "Z", "ROLL", "PITCH", "YAW"])]
    pose: Vec<f64>,
    /// Which frame to place at the pose.
    #[arg(long, value_enum, default_value = "tool0")]
    frame: FrameArg,
    /// Current joints q1 … q6: picks the nearest branch and seeds the QP solver (default all 0);
    /// with --urdf, the chain IK's start, one value per movable joint of the chain (default: 0
    /// within each joint's limits). Flags may follow the list.
    #[arg(long, num_args = 1.., allow_hyphen_values = true, value_parser = crate::cli::args::finite_number, value_name = "Q")]
    current: Option<Vec<f64>>,
    /// Also run the clarabel QP IK from --current (tolerance 1e-4 m / 1e-3 rad). With --urdf
    /// it is accepted and changes nothing: the chain IK is itself this QP solver (damped QP
    /// steps within the joint limits, from --current).
    #[arg(long)]
    qp: bool,
    /// Seed of the QP solver's random restarts, 0–9007199254740991 (2⁵³ − 1).
    #[arg(long, default_value_t = 0, value_parser = super::args::seed)]
    seed: u64,
    #[command(flatten)]
    out: OutputArgs,
}

pub fn run(a: &IkArgs) -> anyhow::Result<ExitCode> {
    let target = pose_from(&a.pose, &a.out, "--pose")?;
    if let Some(path) = &a.urdf {
        let request = super::chain::ChainIkRequest {
            path,
            tip: a.tip.as_deref(),
            pose: target,
            current: a.current.as_deref(),
            seed: a.seed,
        };
        return super::chain::run_ik(&request, &a.out);
    }
    let current = match &a.current {
        Some(values) => joints_from(values, &a.out, "--current")?,
        None => [0.0; 6],
    };
    let answers = IkAnswers::solve(a, target, current);
    if a.out.json {
        print_json(&answers.to_json());
    } else {
        answers.print();
    }
    Ok(if answers.analytic.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// The built-in model's inverse kinematics for one pose: every closed-form branch and, with
/// --qp, the QP solver's answer from `current`.
struct IkAnswers {
    model: ArmModel,
    frame: EndFrame,
    /// The pose to place `frame` at, in `base_link`.
    target: Pose,
    /// --current \[rad\]: picks the nearest branch and starts the QP solver.
    current: [f64; 6],
    analytic: Result<Vec<IkSolution>, IkError>,
    /// The closed-form branches (none when `analytic` failed).
    solutions: Vec<IkSolution>,
    qp: Option<Result<QpIkSolution, QpIkError>>,
}

impl IkAnswers {
    /// Solves `target` with the closed form (wrist singularity resolved to --current's q6) and,
    /// with --qp, the QP solver seeded by --seed.
    fn solve(a: &IkArgs, target: Pose, current: [f64; 6]) -> Self {
        let model = a.model.model();
        let frame = EndFrame::from(a.frame);
        let options = AnalyticIkOptions {
            wrist_singular_q6: current[5],
            ..Default::default()
        };
        let analytic = model.ik_analytic(&target, frame, &options);
        let solutions = analytic.clone().unwrap_or_default();
        let qp = a.qp.then(|| {
            let qp_options = QpIkOptions {
                frame,
                seed: a.seed,
                ..Default::default()
            };
            model.ik_qp(&target, &current, &qp_options)
        });
        IkAnswers {
            model,
            frame,
            target,
            current,
            analytic,
            solutions,
            qp,
        }
    }

    /// The in-limit branch nearest to --current, if any.
    fn nearest(&self) -> Option<IkSolution> {
        nearest_solution(&self.solutions, &self.current)
    }

    /// How far FK of `q` lands from the target: position \[m\] and orientation \[rad\].
    fn fk_error(&self, q: &[f64; 6]) -> (f64, f64) {
        self.model.fk(q, self.frame).distance_to(&self.target)
    }

    /// The answers as one JSON object (`--json`).
    fn to_json(&self) -> serde_json::Value {
        let rows: Vec<_> = self
            .solutions
            .iter()
            .map(|s| {
                let (dp, dr) = self.fk_error(&s.joints);
                json!({"joints": s.joints, "in_limits": s.in_limits, "branch": s.branch,
                       "fk_error_m": dp, "fk_error_rad": dr,
                       "distance_to_current_rad": joint_distance(&s.joints, &self.current)})
            })
            .collect();
        let mut out = json!({
            "model": self.model.kind.name(), "frame": self.frame.name(),
            "target": self.target.record(), "current": self.current, "solutions": rows,
            "nearest": self.nearest().map(|s| s.joints),
        });
        if let Err(e) = &self.analytic {
            out["error"] = json!(e.to_string());
        }
        if let Some(qp) = &self.qp {
            out["qp"] = match qp {
                Ok(s) => json!({"converged": true, "joints": s.joints,
                    "fk_error_m": s.position_error_m, "fk_error_rad": s.orientation_error_rad,
                    "iterations": s.iterations, "attempts": s.attempts}),
                Err(e) => json!({"converged": false, "error": e.to_string()}),
            };
        }
        out
    }

    /// Prints the target, every closed-form branch (the nearest marked) and the QP answer.
    fn print(&self) {
        let name = self.model.kind.name().to_uppercase();
        println!(
            "{name} inverse kinematics for {} in base_link",
            self.frame.name()
        );
        println!(
            "  target xyz {} m, rpy {} deg",
            fmt3(self.target.xyz()),
            fmt3(self.target.rpy().map(f64::to_degrees))
        );
        match &self.analytic {
            Ok(_) => self.print_branches(),
            Err(e) => println!("  no closed-form solution: {e}"),
        }
        if let Some(qp) = &self.qp {
            match qp {
                Ok(s) => println!(
                    "  QP IK   {}  error {:.1e} m / {:.1e} rad, {} QP steps, {} attempt(s)",
                    fmt_joints(&s.joints),
                    s.position_error_m,
                    s.orientation_error_rad,
                    s.iterations,
                    s.attempts
                ),
                Err(e) => println!("  QP IK   failed: {e}"),
            }
        }
    }

    /// One line per closed-form branch: its bits, joints, whether in limits and its FK error;
    /// `*` marks the nearest to --current.
    fn print_branches(&self) {
        let nearest = self.nearest();
        println!(
            "  {} closed-form branches (shoulder/wrist/elbow bits; * = nearest to --current):",
            self.solutions.len()
        );
        for s in &self.solutions {
            let (dp, _) = self.fk_error(&s.joints);
            let mark = if nearest.is_some_and(|n| n.branch == s.branch) {
                "*"
            } else {
                " "
            };
            let limits = if s.in_limits {
                "in limits "
            } else {
                "OUT of limits"
            };
            println!(
                "  {mark}{:03b} {}  {limits}  FK error {dp:.1e} m",
                s.branch,
                fmt_joints(&s.joints)
            );
        }
        if nearest.is_none() {
            println!("  no branch is within the joint limits");
        }
    }
}
