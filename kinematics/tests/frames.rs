//! Poses and frames: conventions, inverses, and a rotated base.

use std::f64::consts::{FRAC_PI_2, PI};

use fairgrasp_kinematics::pose::{
    PoseError, base_pose_to_world, naive_world_to_base, world_pose_to_base,
};
use fairgrasp_kinematics::{Pose, base_to_world, world_to_base};

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn rpy_is_fixed_axis_x_then_y_then_z() {
    // Yaw 90 deg alone turns x into y.
    let yaw = Pose::from_xyz_rpy([0.0; 3], [0.0, 0.0, FRAC_PI_2]);
    assert!(close(
        yaw.transform_vector([1.0, 0.0, 0.0]),
        [0.0, 1.0, 0.0],
        1e-12
    ));
    // Roll 90 then yaw 90 (fixed axes): z -> -y (roll) -> x (yaw).
    let both = Pose::from_xyz_rpy([0.0; 3], [FRAC_PI_2, 0.0, FRAC_PI_2]);
    assert!(close(
        both.transform_vector([0.0, 0.0, 1.0]),
        [1.0, 0.0, 0.0],
        1e-12
    ));
}

#[test]
fn rpy_and_quaternion_round_trip() {
    for rpy in [[0.1, -0.4, 2.0], [-2.5, 1.2, -0.3], [PI - 0.01, 0.0, 0.5]] {
        let pose = Pose::from_xyz_rpy([0.1, 0.2, 0.3], rpy);
        let back = pose.rpy();
        assert!(close(back, rpy, 1e-12), "{rpy:?} -> {back:?}");
        let q = pose.quat_xyzw();
        let again = Pose::try_from_xyz_quat_xyzw(pose.xyz(), q).unwrap();
        let (dp, dr) = again.distance_to(&pose);
        assert!(dp < 1e-12 && dr < 1e-12);
    }
    // Quaternion order is x, y, z, w: yaw 90 deg is [0, 0, sin 45, cos 45].
    let q = Pose::from_xyz_rpy([0.0; 3], [0.0, 0.0, FRAC_PI_2]).quat_xyzw();
    let h = (0.5f64).sqrt();
    assert!(
        (q[0]).abs() < 1e-12
            && q[1].abs() < 1e-12
            && (q[2] - h).abs() < 1e-12
            && (q[3] - h).abs() < 1e-12
    );
}

#[test]
fn a_quaternion_that_is_not_unit_is_refused_and_nan_is_named() {
    let err = Pose::try_from_xyz_quat_xyzw([0.0; 3], [0.0, 0.0, 0.0, 2.0]).unwrap_err();
    assert!(matches!(err, PoseError::NotUnitQuaternion { .. }), "{err}");
    let err = Pose::try_from_xyz_rpy([0.0, f64::NAN, 0.0], [0.0; 3]).unwrap_err();
    assert!(err.to_string().contains("xyz"), "{err}");
}

#[test]
fn compose_with_inverse_is_identity() {
    let a = Pose::from_xyz_rpy([0.3, -0.2, 0.5], [0.4, -0.7, 2.2]);
    let (dp, dr) = a.compose(&a.inverse()).distance_to(&Pose::identity());
    assert!(dp < 1e-15 && dr < 1e-7);
}

#[test]
fn compose_applies_the_right_transform_first() {
    // T_a_b translates by x; T_b_c rotates 90 deg about z. A point on c's x axis lands on a's
    // (1, 1, 0): rotated first (to b's y axis), then translated.
    let a_b = Pose::from_xyz([1.0, 0.0, 0.0]);
    let b_c = Pose::from_xyz_rpy([0.0; 3], [0.0, 0.0, FRAC_PI_2]);
    let p = a_b.compose(&b_c).transform_point([1.0, 0.0, 0.0]);
    assert!(close(p, [1.0, 1.0, 0.0], 1e-12), "{p:?}");
}

#[test]
fn world_to_base_with_a_rotated_base_differs_from_subtracting_positions() {
    // The arm stands at (0.5, 0.2, 0.75) on a table, turned 90 deg about z.
    let base = Pose::from_xyz_rpy([0.5, 0.2, 0.75], [0.0, 0.0, FRAC_PI_2]);
    let cube_world = [0.5, 0.6, 0.775];
    let right = world_to_base(&base, cube_world);
    let naive = naive_world_to_base(&base, cube_world);
    // 0.4 m along world y is 0.4 m along the base's x axis.
    assert!(close(right, [0.4, 0.0, 0.025], 1e-12), "{right:?}");
    assert!(close(naive, [0.0, 0.4, 0.025], 1e-12), "{naive:?}");
    let gap = ((right[0] - naive[0]).powi(2) + (right[1] - naive[1]).powi(2)).sqrt();
    assert!(gap > 0.5, "subtracting positions is off by {gap} m");
    // Back to the world exactly.
    assert!(close(base_to_world(&base, right), cube_world, 1e-12));
}

#[test]
fn naive_subtraction_is_right_only_for_an_unrotated_base() {
    let base = Pose::from_xyz([0.5, 0.2, 0.75]);
    let p = [0.1, -0.3, 0.9];
    assert!(close(
        world_to_base(&base, p),
        naive_world_to_base(&base, p),
        1e-15
    ));
}

#[test]
fn poses_move_between_world_and_base_with_any_base_rotation() {
    let base = Pose::from_xyz_rpy([0.2, -0.1, 0.8], [0.3, -0.2, 1.9]);
    let target_world = Pose::from_xyz_rpy([0.6, 0.1, 0.9], [PI, 0.1, -0.4]);
    let in_base = world_pose_to_base(&base, &target_world);
    let back = base_pose_to_world(&base, &in_base);
    let (dp, dr) = back.distance_to(&target_world);
    assert!(dp < 1e-12 && dr < 1e-7);
    // The point view agrees with the pose view.
    assert!(close(
        in_base.xyz(),
        world_to_base(&base, target_world.xyz()),
        1e-12
    ));
}
