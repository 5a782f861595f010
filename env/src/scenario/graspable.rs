//! What "graspable" means, once: a top-down TCP pose at the object whose IK branch is within the
//! joint limits and free of self-collision and table contact ([`feasible_solutions`]), with a
//! pre-grasp pose above it on the same branch ([`top_down_grasp`]). Scenario sampling keeps
//! only graspable objects; the planner (`planner/src/grasp.rs`) plans its grasps from the same
//! feasible solutions.
//!
//! Frames: poses in `base_link`; positions and yaws of objects in the table frame ([`Mount`]).

use std::f64::consts::{FRAC_PI_2, PI};

use fairgrasp_kinematics::analytic_ik::joint_distance;
use fairgrasp_kinematics::{AnalyticIkOptions, ArmModel, EndFrame, IkSolution, Pose};

use crate::cell::mount::Mount;

/// Height of the pre-grasp pose above the grasp pose \[m\].
pub const PRE_GRASP_HEIGHT: f64 = 0.10;

/// The TCP pose in `base_link` for a top-down grasp at `xyz` (table frame) \[m\]: tool z along
/// world gravity (down), the fingers closing across the table-frame direction `yaw` + 90° \[rad\].
pub fn top_down_in_base(mount: &Mount, xyz: [f64; 3], yaw: f64) -> Pose {
    mount.table_to_base(&Pose::from_xyz_rpy(xyz, [PI, 0.0, yaw]))
}

/// The in-limit top-down grasp (TCP at the object centre, tool z along world gravity, fingers
/// across a pair of faces) and its pre-grasp 10 cm above (along the world vertical), as joint
/// angles: among the yaws `yaw + k·90°` and the IK branches that admit both within the joint
/// limits and without self-collision or table contact, the pair whose pre-grasp is nearest to
/// `current` \[rad\]. `None` if none does.
pub fn top_down_grasp(
    model: &ArmModel,
    mount: &Mount,
    object_in_base: &Pose,
    current: &[f64; 6],
) -> Option<([f64; 6], [f64; 6])> {
    let xyz = mount.base_to_table(object_in_base).xyz();
    let yaw = mount.yaw_on_table(object_in_base);
    let table = &mount.table_in_base;
    let options = AnalyticIkOptions::default();
    let mut best: Option<(f64, [f64; 6], [f64; 6])> = None;
    for k in 0..4 {
        let grasp_yaw = yaw + k as f64 * FRAC_PI_2;
        let grasp = top_down_in_base(mount, xyz, grasp_yaw);
        let above = top_down_in_base(
            mount,
            [xyz[0], xyz[1], xyz[2] + PRE_GRASP_HEIGHT],
            grasp_yaw,
        );
        let Ok(grasps) = model.ik_analytic(&grasp, EndFrame::Tcp, &options) else {
            continue;
        };
        let Ok(aboves) = model.ik_analytic(&above, EndFrame::Tcp, &options) else {
            continue;
        };
        for g in feasible_solutions(model, &grasps, table) {
            if let Some(a) =
                feasible_solutions(model, &aboves, table).find(|a| a.branch == g.branch)
            {
                let d = joint_distance(&a.joints, current);
                if best.is_none_or(|(bd, _, _)| d < bd) {
                    best = Some((d, g.joints, a.joints));
                }
            }
        }
    }
    best.map(|(_, g, a)| (g, a))
}

/// Clearance every part but the base keeps above the table top \[m\].
pub const TABLE_CLEARANCE: f64 = 0.002;

/// No self-collision (capsules), and nothing but the base lower than [`TABLE_CLEARANCE`] above
/// the table top, measured along the world vertical (`table_in_base`: the table frame in
/// `base_link`, [`Mount::table_in_base`]).
pub fn collision_free(model: &ArmModel, q: &[f64; 6], table_in_base: &Pose) -> bool {
    model.self_collisions(q, 0.0).is_empty()
        && model.lowest_point_in(q, table_in_base) > TABLE_CLEARANCE
}

/// The IK solutions of a top-down pose that a grasp may use: within the joint limits and
/// [`collision_free`] (`table_in_base`: the table frame in `base_link`).
pub fn feasible_solutions<'a>(
    model: &'a ArmModel,
    solutions: &'a [IkSolution],
    table_in_base: &'a Pose,
) -> impl Iterator<Item = &'a IkSolution> + 'a {
    solutions
        .iter()
        .filter(move |s| s.in_limits && collision_free(model, &s.joints, table_in_base))
}
