//! Grasp poses from the observed object, and their joint targets.
//!
//! A top-down grasp puts the TCP at the cube centre with the tool z axis pointing down and the
//! fingers closing across a pair of faces. The cube repeats every 90°, so of the yaws
//! `yaw + k·90°` the one closest to the current TCP yaw is tried first (the wrist turns least).

use std::f64::consts::{FRAC_PI_2, PI};

use fairgrasp_env::randomize::collision_free;
use fairgrasp_kinematics::analytic_ik::{joint_distance, wrap_pi};
use fairgrasp_kinematics::{AnalyticIkOptions, ArmModel, EndFrame, Pose, QpIkOptions};
use serde::Serialize;

/// The three poses of a grasp, TCP in `base_link`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GraspPoses {
    /// Above the object by `pre_grasp_height`.
    pub pre_grasp: Pose,
    /// At the object centre.
    pub grasp: Pose,
    /// Above the grasp by `lift_height`.
    pub lift: Pose,
}

/// Joint targets for the three poses, one IK branch for all.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GraspJoints {
    pub pre_grasp: [f64; 6],
    pub grasp: [f64; 6],
    pub lift: [f64; 6],
    /// TCP yaw of the chosen grasp [rad].
    pub yaw: f64,
    /// Whether the QP IK was needed (no closed-form branch within the limits).
    pub used_qp_fallback: bool,
}

/// The top-down TCP pose at `xyz` with yaw `yaw` (tool z down: roll π).
pub fn top_down(xyz: [f64; 3], yaw: f64) -> Pose {
    Pose::from_xyz_rpy(xyz, [PI, 0.0, yaw])
}

/// Yaw of the TCP's x axis about base z [rad].
pub fn tcp_yaw(model: &ArmModel, q: &[f64; 6]) -> f64 {
    let x = model.fk_tcp(q).transform_vector([1.0, 0.0, 0.0]);
    x[1].atan2(x[0])
}

/// The candidate grasp yaws `object_yaw + k·90°`, closest to `current_yaw` first.
pub fn candidate_yaws(object_yaw: f64, current_yaw: f64) -> [f64; 4] {
    let mut yaws = [0, 1, 2, 3].map(|k| object_yaw + k as f64 * FRAC_PI_2);
    yaws.sort_by(|a, b| {
        wrap_pi(a - current_yaw)
            .abs()
            .total_cmp(&wrap_pi(b - current_yaw).abs())
    });
    yaws
}

/// The grasp poses for an object centre and yaw (both in `base_link`).
pub fn grasp_poses(
    object: [f64; 3],
    yaw: f64,
    pre_grasp_height: f64,
    lift_height: f64,
) -> GraspPoses {
    let above = |h: f64| top_down([object[0], object[1], object[2] + h], yaw);
    GraspPoses {
        pre_grasp: above(pre_grasp_height),
        grasp: above(0.0),
        lift: above(lift_height),
    }
}

/// IK for `pose` nearest to `near`: the closed-form branch within the limits and free of
/// collisions (self and table, the table top at `table_z`), else the QP IK started from `near`.
/// Returns the joints and whether the QP was used.
fn solve(model: &ArmModel, pose: &Pose, near: &[f64; 6], table_z: f64) -> Option<([f64; 6], bool)> {
    let options = AnalyticIkOptions {
        wrist_singular_q6: near[5],
        ..AnalyticIkOptions::default()
    };
    if let Ok(solutions) = model.ik_analytic(pose, EndFrame::Tcp, &options)
        && let Some(best) = solutions
            .iter()
            .filter(|s| s.in_limits && collision_free(model, &s.joints, table_z))
            .min_by(|a, b| {
                joint_distance(&a.joints, near).total_cmp(&joint_distance(&b.joints, near))
            })
    {
        return Some((best.joints, false));
    }
    let qp = QpIkOptions {
        frame: EndFrame::Tcp,
        max_attempts: 1,
        max_iterations: 100,
        ..QpIkOptions::default()
    };
    let solution = model.ik_qp(pose, near, &qp).ok()?;
    collision_free(model, &solution.joints, table_z).then_some((solution.joints, true))
}

/// Where the grasp is: the object centre and yaw and the table top height, in `base_link`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GraspTarget {
    /// Object centre [m].
    pub object: [f64; 3],
    /// Object yaw about base z [rad].
    pub object_yaw: f64,
    /// Table top height [m].
    pub table_z: f64,
}

/// Joint targets for a top-down grasp of `target` starting from `current`; `None` if no yaw
/// admits all three poses within the limits and without collisions.
pub fn plan_grasp_joints(
    model: &ArmModel,
    target: &GraspTarget,
    current: &[f64; 6],
    pre_grasp_height: f64,
    lift_height: f64,
) -> Option<GraspJoints> {
    let table_z = target.table_z;
    for yaw in candidate_yaws(target.object_yaw, tcp_yaw(model, current)) {
        let poses = grasp_poses(target.object, yaw, pre_grasp_height, lift_height);
        let Some((pre_grasp, qp1)) = solve(model, &poses.pre_grasp, current, table_z) else {
            continue;
        };
        let Some((grasp, qp2)) = solve(model, &poses.grasp, &pre_grasp, table_z) else {
            continue;
        };
        let Some((lift, qp3)) = solve(model, &poses.lift, &grasp, table_z) else {
            continue;
        };
        // One branch for the whole grasp: the straight descent must not swing the elbow over.
        if joint_distance(&pre_grasp, &grasp) > 1.0 || joint_distance(&grasp, &lift) > 1.0 {
            continue;
        }
        return Some(GraspJoints {
            pre_grasp,
            grasp,
            lift,
            yaw,
            used_qp_fallback: qp1 || qp2 || qp3,
        });
    }
    None
}
