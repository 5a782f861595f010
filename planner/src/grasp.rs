//! Grasp poses from the observed object, and their joint targets.
//!
//! A top-down grasp puts the TCP at the cube centre with the tool z axis pointing down along
//! world gravity and the fingers closing across a pair of faces. Poses are built in the table
//! frame (z up along the world vertical, see [`Mount`]) and expressed in `base_link` through
//! the mount, so a tilted or raised base changes nothing about what "top-down" and "above" mean. The cube repeats every 90°, so of the yaws
//! `yaw + k·90°` the one closest to the current TCP yaw is tried first (the wrist turns least).

use std::f64::consts::FRAC_PI_2;

use fairgrasp_env::Mount;
use fairgrasp_env::scenario::graspable::{collision_free, feasible_solutions, top_down_in_base};
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

/// The object pose a plan was made on, `base_link`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PlannedObject {
    /// Object centre \[m\].
    pub position: [f64; 3],
    /// Object yaw about the world vertical, relative to the base's heading \[rad\].
    pub yaw: f64,
}

/// Joint targets for the three poses, one IK branch for all.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GraspJoints {
    pub pre_grasp: [f64; 6],
    pub grasp: [f64; 6],
    pub lift: [f64; 6],
    /// TCP yaw of the chosen grasp \[rad\].
    pub yaw: f64,
    /// Whether the QP IK was needed (no closed-form branch within the limits).
    pub used_qp_fallback: bool,
}

/// Yaw of the TCP's x axis about the world vertical, relative to the base's heading \[rad\].
pub fn tcp_yaw(model: &ArmModel, mount: &Mount, q: &[f64; 6]) -> f64 {
    mount.yaw_on_table(&model.fk_tcp(q))
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

/// The grasp poses, TCP in `base_link`, for an object centre \[m\] and grasp yaw \[rad\] given in
/// the table frame: pre-grasp and lift straight above along the world vertical.
pub fn grasp_poses(
    mount: &Mount,
    object: [f64; 3],
    yaw: f64,
    pre_grasp_height: f64,
    lift_height: f64,
) -> GraspPoses {
    let above = |h: f64| top_down_in_base(mount, [object[0], object[1], object[2] + h], yaw);
    GraspPoses {
        pre_grasp: above(pre_grasp_height),
        grasp: above(0.0),
        lift: above(lift_height),
    }
}

/// IK for `pose` nearest to `near`: the feasible closed-form branch (the env's definition of
/// graspable, `feasible_solutions`; `table`: the table frame in `base_link`) nearest to `near`,
/// else the QP IK started from `near`, if collision-free. Returns the joints and whether the QP was used.
fn solve(model: &ArmModel, pose: &Pose, near: &[f64; 6], table: &Pose) -> Option<([f64; 6], bool)> {
    let options = AnalyticIkOptions {
        wrist_singular_q6: near[5],
        ..AnalyticIkOptions::default()
    };
    if let Ok(solutions) = model.ik_analytic(pose, EndFrame::Tcp, &options)
        && let Some(best) = feasible_solutions(model, &solutions, table).min_by(|a, b| {
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
    collision_free(model, &solution.joints, table).then_some((solution.joints, true))
}

/// Where the grasp is: the observed object and the arm's mount.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GraspTarget {
    /// Object centre in `base_link` \[m\].
    pub object: [f64; 3],
    /// Object yaw about the world vertical, relative to the base's heading \[rad\] (as observed).
    pub object_yaw: f64,
    /// The base and the table frame (what "down" and "the table top" are in `base_link`).
    pub mount: Mount,
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
    let mount = &target.mount;
    let table = &mount.table_in_base;
    let object = mount.table_in_base.inverse().transform_point(target.object);
    for yaw in candidate_yaws(target.object_yaw, tcp_yaw(model, mount, current)) {
        let poses = grasp_poses(mount, object, yaw, pre_grasp_height, lift_height);
        let Some((pre_grasp, qp1)) = solve(model, &poses.pre_grasp, current, table) else {
            continue;
        };
        let Some((grasp, qp2)) = solve(model, &poses.grasp, &pre_grasp, table) else {
            continue;
        };
        let Some((lift, qp3)) = solve(model, &poses.lift, &grasp, table) else {
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
