//! Forward kinematics: FAIRINO's check values, DH = URDF = k, Jacobian = finite differences.

mod common;

use fairgrasp_kinematics::fairino::{FR3_ZERO_FLANGE_ROTATION, FR3_ZERO_FLANGE_XYZ};
use fairgrasp_kinematics::fk::EndFrame;
use fairgrasp_kinematics::{
    ArmKind, FR3_URDF, FR5_URDF, UrdfRobot, manipulability, min_singular_value,
};

#[test]
fn fr3_zero_pose_flange_matches_fairinos_check_values() {
    let model = ArmKind::Fr3.model();
    let flange = model.fk_flange(&[0.0; 6]);
    let xyz = flange.xyz();
    for i in 0..3 {
        assert!((xyz[i] - FR3_ZERO_FLANGE_XYZ[i]).abs() < 1e-12, "{xyz:?}");
    }
    let rotation = flange.rotation_rows();
    for r in 0..3 {
        for c in 0..3 {
            assert!(
                (rotation[r][c] - FR3_ZERO_FLANGE_ROTATION[r][c]).abs() < 1e-12,
                "{rotation:?}"
            );
        }
    }
    // The TCP is 0.14 m along the flange z axis (the published rotation's third column: base -y).
    let tcp = model.fk_tcp(&[0.0; 6]).xyz();
    for i in 0..3 {
        let expected = FR3_ZERO_FLANGE_XYZ[i] + 0.14 * FR3_ZERO_FLANGE_ROTATION[i][2];
        assert!((tcp[i] - expected).abs() < 1e-12, "{tcp:?}");
    }
}

#[test]
fn fr3_reach_is_0_622_m() {
    assert!((ArmKind::Fr3.model().reach() - 0.622).abs() < 1e-12);
}

fn dh_equals_urdf(kind: ArmKind, urdf: &str, tip: &str, frame: EndFrame, seed: u64) {
    let model = kind.model();
    let robot = UrdfRobot::from_str_named(urdf, "asset").unwrap();
    let chain = robot.chain(Some(tip)).unwrap();
    assert_eq!(chain.joint_names(), ["j1", "j2", "j3", "j4", "j5", "j6"]);
    let mut rng = common::rng(seed);
    let mut worst = (0.0_f64, 0.0_f64);
    for _ in 0..1000 {
        let q = common::random_in_limits(&model, &mut rng);
        let (dp, dr) = model.fk(&q, frame).distance_to(&chain.fk(&q));
        worst = (worst.0.max(dp), worst.1.max(dr));
    }
    assert!(
        worst.0 <= 1e-9 && worst.1 <= 1e-9,
        "{kind:?} {tip}: worst {worst:?}"
    );
}

#[test]
fn fr3_dh_fk_equals_urdf_chain_fk_on_1000_random_configurations() {
    dh_equals_urdf(ArmKind::Fr3, FR3_URDF, "tool0", EndFrame::Flange, 11);
    dh_equals_urdf(ArmKind::Fr3, FR3_URDF, "tcp", EndFrame::Tcp, 12);
}

#[test]
fn fr5_dh_fk_equals_urdf_chain_fk_on_1000_random_configurations() {
    dh_equals_urdf(ArmKind::Fr5, FR5_URDF, "tool0", EndFrame::Flange, 13);
}

#[test]
fn urdf_chain_fk_equals_the_k_crate_on_the_same_file() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/fr3.urdf");
    let k_chain = k::Chain::<f64>::from_urdf_file(path).unwrap();
    let k_serial = k::SerialChain::from_end(k_chain.find("palm_tcp").unwrap());
    let chain = UrdfRobot::from_file(path)
        .unwrap()
        .chain(Some("tcp"))
        .unwrap();
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(14);
    for _ in 0..300 {
        let q = common::random_in_limits(&model, &mut rng);
        k_serial.set_joint_positions_clamped(&q);
        let theirs = k_serial.end_transform();
        let ours = chain.fk(&q).xyz();
        let t = theirs.translation.vector;
        let err =
            ((ours[0] - t.x).powi(2) + (ours[1] - t.y).powi(2) + (ours[2] - t.z).powi(2)).sqrt();
        assert!(err < 1e-9, "q = {q:?}: ours {ours:?}, k {t:?}");
    }
}

#[test]
fn geometric_jacobian_matches_finite_differences() {
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(15);
    let h = 1e-6;
    for frame in [EndFrame::Flange, EndFrame::Tcp] {
        for _ in 0..200 {
            let q = common::random_in_limits(&model, &mut rng);
            let jac = model.jacobian(&q, frame);
            for i in 0..6 {
                let mut qp = q;
                let mut qm = q;
                qp[i] += h;
                qm[i] -= h;
                let (tp, tm) = (model.fk(&qp, frame), model.fk(&qm, frame));
                let (pp, pm) = (tp.xyz(), tm.xyz());
                // Angular velocity from the relative rotation, expressed in the base frame.
                let w = (tp.iso.rotation * tm.iso.rotation.inverse()).scaled_axis() / (2.0 * h);
                for r in 0..3 {
                    let linear = (pp[r] - pm[r]) / (2.0 * h);
                    assert!(
                        (jac[(r, i)] - linear).abs() < 1e-7,
                        "{frame:?} col {i} row {r}"
                    );
                    assert!(
                        (jac[(r + 3, i)] - w[r]).abs() < 1e-7,
                        "{frame:?} col {i} row {}",
                        r + 3
                    );
                }
            }
        }
    }
}

#[test]
fn manipulability_and_min_singular_value_vanish_at_the_wrist_singularity() {
    let model = ArmKind::Fr3.model();
    let regular = model.jacobian(&[0.3, -1.2, 1.1, -1.4, 0.8, 0.5], EndFrame::Flange);
    let singular = model.jacobian(&[0.3, -1.2, 1.1, -1.4, 0.0, 0.5], EndFrame::Flange);
    assert!(
        manipulability(&regular) > 1e-3,
        "{}",
        manipulability(&regular)
    );
    assert!(min_singular_value(&regular) > 1e-2);
    assert!(
        manipulability(&singular) < 1e-8,
        "{}",
        manipulability(&singular)
    );
    assert!(min_singular_value(&singular) < 1e-9);
}

#[test]
fn the_elbow_stretched_straight_is_singular() {
    let model = ArmKind::Fr3.model();
    let stretched = model.jacobian(&[0.3, -1.2, 0.0, -1.4, 0.8, 0.5], EndFrame::Flange);
    assert!(min_singular_value(&stretched) < 1e-9);
}

#[test]
fn link_poses_equal_the_urdf_link_frames() {
    let model = ArmKind::Fr3.model();
    let robot = UrdfRobot::from_str_named(FR3_URDF, "fr3.urdf").unwrap();
    let mut rng = common::rng(16);
    for _ in 0..200 {
        let q = common::random_in_limits(&model, &mut rng);
        let poses = model.link_poses(&q);
        for (i, link) in model.links.iter().enumerate().skip(1) {
            let chain = robot.chain(Some(link)).unwrap();
            let (dp, dr) = chain.fk(&q[..i]).distance_to(&poses[i].into());
            assert!(dp < 1e-12 && dr < 1e-9, "{link}: {dp:e} {dr:e}");
        }
    }
}

#[test]
fn the_flange_of_the_one_pass_link_poses_is_bit_for_bit_fk_flange() {
    // The env places its links and gripper from one pass down the chain: a replay must not
    // move by a bit against the flange `fk_flange` computes on its own.
    for model in [ArmKind::Fr3.model(), ArmKind::Fr5.model()] {
        let mut rng = common::rng(61);
        for _ in 0..500 {
            let q = common::random_in_limits(&model, &mut rng);
            let (_, flange) = model.link_poses_and_flange(&q);
            assert_eq!(flange.iso, model.fk_flange(&q).iso, "{q:?}");
        }
    }
}
