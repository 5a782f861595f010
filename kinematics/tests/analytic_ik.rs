//! Closed-form IK: round trips, branch selection and unreachable targets.

mod common;

use fairgrasp_kinematics::analytic_ik::{joint_distance, wrap_pi};
use fairgrasp_kinematics::{AnalyticIkOptions, ArmKind, EndFrame, IkError, Pose};

fn round_trip(kind: ArmKind, frame: EndFrame, samples: usize, seed: u64) {
    let model = kind.model();
    let mut rng = common::rng(seed);
    let options = AnalyticIkOptions::default();
    let mut worst_fk = 0.0_f64;
    for n in 0..samples {
        let q = common::random_in_limits(&model, &mut rng);
        let target = model.fk(&q, frame);
        let solutions = model
            .ik_analytic(&target, frame, &options)
            .unwrap_or_else(|e| panic!("sample {n}: q = {q:?}: {e}"));
        assert!(solutions.len() <= 8);
        for s in &solutions {
            let (dp, dr) = model.fk(&s.joints, frame).distance_to(&target);
            worst_fk = worst_fk.max(dp);
            assert!(
                dp <= 1e-9 && dr <= 1e-8,
                "sample {n}: branch {} misses by {dp:e} m / {dr:e} rad",
                s.branch
            );
            assert!(s.joints.iter().all(|v| v.is_finite()));
            assert_eq!(s.in_limits, model.in_limits(&s.joints, 1e-9));
        }
        let closest = solutions
            .iter()
            .map(|s| common::max_abs_diff(&s.joints, &q))
            .fold(f64::INFINITY, f64::min);
        assert!(
            closest < 1e-6,
            "sample {n}: q = {q:?} not among the branches (closest {closest:e} rad)"
        );
    }
    eprintln!("{kind:?} {frame:?}: worst FK(IK(T)) error {worst_fk:e} m over {samples} samples");
}

#[test]
fn fr3_flange_round_trip_recovers_the_original_joints_on_10000_random_configurations() {
    round_trip(ArmKind::Fr3, EndFrame::Flange, 10_000, 1);
}

#[test]
fn fr3_tcp_round_trip_recovers_the_original_joints() {
    round_trip(ArmKind::Fr3, EndFrame::Tcp, 2_000, 2);
}

#[test]
fn fr5_round_trip_recovers_the_original_joints() {
    round_trip(ArmKind::Fr5, EndFrame::Flange, 2_000, 3);
}

#[test]
fn top_down_poses_in_front_of_the_base_have_eight_distinct_branches() {
    let model = ArmKind::Fr3.model();
    for xyz in [[0.3, 0.0, 0.2], [0.25, 0.1, 0.15], [0.0, -0.35, 0.25]] {
        let target = Pose::from_xyz_rpy(xyz, [std::f64::consts::PI, 0.0, 0.3]);
        let solutions = model
            .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
            .unwrap();
        assert_eq!(solutions.len(), 8, "{xyz:?}");
        let mut branches: Vec<u8> = solutions.iter().map(|s| s.branch).collect();
        branches.sort();
        assert_eq!(branches, (0..8).collect::<Vec<u8>>());
        for (i, a) in solutions.iter().enumerate() {
            for b in &solutions[i + 1..] {
                let differs = a
                    .joints
                    .iter()
                    .zip(&b.joints)
                    .any(|(x, y)| wrap_pi(x - y).abs() > 1e-6);
                assert!(
                    differs,
                    "{xyz:?}: branches {} and {} coincide",
                    a.branch, b.branch
                );
            }
        }
    }
}

#[test]
fn angles_are_moved_into_the_j2_and_j4_limits_beyond_minus_pi() {
    let model = ArmKind::Fr3.model();
    // j2 = -200 deg and j4 = -250 deg lie below -pi: atan2 gives +160 deg and +110 deg.
    let q = [
        0.2,
        (-200.0f64).to_radians(),
        0.9,
        (-250.0f64).to_radians(),
        1.0,
        -0.4,
    ];
    assert!(model.in_limits(&q, 0.0));
    let solutions = model
        .ik_analytic(
            &model.fk_flange(&q),
            EndFrame::Flange,
            &AnalyticIkOptions::default(),
        )
        .unwrap();
    let matching = solutions
        .iter()
        .find(|s| common::max_abs_diff(&s.joints, &q) < 1e-9);
    let found = matching.expect("the original configuration is a branch, with j2 and j4 below -pi");
    assert!(found.in_limits);
}

#[test]
fn nearest_selection_returns_the_in_limit_branch_closest_to_the_current_joints() {
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(7);
    for _ in 0..500 {
        let q = common::random_in_limits(&model, &mut rng);
        let target = model.fk_flange(&q);
        let nearest = model
            .ik_nearest(&target, EndFrame::Flange, &q)
            .unwrap()
            .unwrap();
        assert!(common::max_abs_diff(&nearest.joints, &q) < 1e-6);
        // Its distance is the minimum over all in-limit branches.
        let all = model
            .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
            .unwrap();
        for s in all.iter().filter(|s| s.in_limits) {
            assert!(joint_distance(&nearest.joints, &q) <= joint_distance(&s.joints, &q) + 1e-12);
        }
    }
}

#[test]
fn a_target_beyond_the_reach_is_an_out_of_reach_error() {
    let model = ArmKind::Fr3.model();
    let target = Pose::from_xyz_rpy([1.0, 0.2, 0.3], [3.1, 0.0, 0.0]);
    let err = model
        .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
        .unwrap_err();
    assert!(matches!(err, IkError::OutOfReach { .. }), "{err}");
    assert!(err.to_string().contains("elbow cannot span"), "{err}");
}

#[test]
fn a_wrist_centre_inside_the_d4_cylinder_is_an_out_of_reach_error() {
    let model = ArmKind::Fr3.model();
    // Flange pointing down (z6 = -z) 0.05 m from the joint-1 axis: p5 is 0.05 m from it, < d4.
    let target = Pose::from_xyz_rpy([0.05, 0.0, 0.3], [std::f64::consts::PI, 0.0, 0.0]);
    let err = model
        .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
        .unwrap_err();
    assert!(err.to_string().contains("offset cylinder"), "{err}");
}

#[test]
fn a_wrist_centre_on_the_joint_1_axis_is_shoulder_singular() {
    let model = ArmKind::Fr3.model();
    let target = Pose::from_xyz_rpy([0.0, 0.0, 0.4], [std::f64::consts::PI, 0.0, 0.0]);
    let err = model
        .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
        .unwrap_err();
    assert!(matches!(err, IkError::ShoulderSingular { .. }), "{err}");
}

#[test]
fn a_wrist_singular_pose_uses_the_given_q6_and_still_reaches_the_target() {
    let model = ArmKind::Fr3.model();
    let q = [0.4, -1.0, 1.2, -0.7, 0.0, 0.3]; // theta5 = 0: joints 4 and 6 align
    let target = model.fk_flange(&q);
    let options = AnalyticIkOptions {
        wrist_singular_q6: 0.3,
        ..Default::default()
    };
    let solutions = model
        .ik_analytic(&target, EndFrame::Flange, &options)
        .unwrap();
    assert!(
        solutions
            .iter()
            .any(|s| common::max_abs_diff(&s.joints, &q) < 1e-6)
    );
    for s in &solutions {
        let (dp, dr) = model.fk_flange(&s.joints).distance_to(&target);
        assert!(dp < 1e-9 && dr < 1e-8, "{dp:e} {dr:e}");
    }
}

#[test]
fn a_non_finite_target_is_an_error_not_nan_joints() {
    let model = ArmKind::Fr3.model();
    let target = Pose::from_xyz([f64::NAN, 0.2, 0.3]);
    let err = model
        .ik_analytic(&target, EndFrame::Flange, &AnalyticIkOptions::default())
        .unwrap_err();
    assert_eq!(err, IkError::NonFinite);
}
