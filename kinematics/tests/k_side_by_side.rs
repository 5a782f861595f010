//! fairgrasp's URDF chains against the `k` crate's (openrr), both built from the same
//! `urdf_rs::Robot`: the tip's pose and the geometric Jacobian agree on random in-limit
//! configurations of the shipped arms. The timing side of the comparison is the bench
//! `k_side_by_side`; both are summed up in docs/kinematics.md.

mod common;

use fairgrasp_kinematics::urdf::urdf_rs;
use fairgrasp_kinematics::{FR3_URDF, FR5_URDF, SerialChain, UrdfRobot};
use rand::Rng;

/// The arms compared: file, text and tip link (`None`: the only leaf).
const ARMS: [(&str, &str, Option<&str>); 3] = [
    ("fr3.urdf", FR3_URDF, Some("tool0")),
    ("fr5.urdf", FR5_URDF, Some("tool0")),
    (
        "seven_joint_arm.urdf",
        include_str!("../../assets/seven_joint_arm.urdf"),
        None,
    ),
];

/// fairgrasp's chain and k's, root to `tip`, from one reading of `text`.
fn both_chains(file: &str, text: &str, tip: Option<&str>) -> (SerialChain, k::SerialChain<f64>) {
    let ours = UrdfRobot::from_str_named(text, file)
        .unwrap()
        .chain(tip)
        .unwrap();
    let robot = urdf_rs::read_from_string(text).unwrap();
    let tree = k::Chain::<f64>::from(&robot);
    let end = tree.find_link(&ours.tip).unwrap();
    (ours, k::SerialChain::from_end(end))
}

/// A configuration within the chain's limits (continuous joints: ±π) \[rad or m\].
fn random_configuration(chain: &SerialChain, rng: &mut impl Rng) -> Vec<f64> {
    chain
        .joints
        .iter()
        .filter(|j| j.kind.is_single_axis())
        .map(|j| {
            let [lower, upper] = j
                .limits
                .unwrap_or([-std::f64::consts::PI, std::f64::consts::PI]);
            rng.random_range(lower..=upper)
        })
        .collect()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn fk_and_jacobian_agree_with_k_on_random_configurations_of_the_shipped_arms() {
    let mut rng = common::rng(51);
    for (file, text, tip) in ARMS {
        let (ours, theirs) = both_chains(file, text, tip);
        assert_eq!(ours.dof(), theirs.dof(), "{file}");
        let (mut worst_pose, mut worst_jacobian) = (0.0f64, 0.0f64);
        for _ in 0..500 {
            let q = random_configuration(&ours, &mut rng);
            theirs.set_joint_positions(&q).unwrap();
            theirs.update_transforms();
            let (pose, jacobian) = ours.fk_jacobian(&q);
            let k_pose = theirs.end_transform().to_homogeneous();
            let k_jacobian = k::jacobian(&theirs);
            assert_eq!(k_jacobian.shape(), jacobian.shape(), "{file}");
            worst_pose = worst_pose.max(largest_difference(
                pose.iso.to_homogeneous().as_slice(),
                k_pose.as_slice(),
            ));
            worst_jacobian = worst_jacobian.max(largest_difference(
                jacobian.as_slice(),
                k_jacobian.as_slice(),
            ));
        }
        eprintln!(
            "{file}: largest difference pose {worst_pose:.1e}, Jacobian {worst_jacobian:.1e}"
        );
        assert!(worst_pose < 1e-12, "{file}: pose differs by {worst_pose}");
        assert!(
            worst_jacobian < 1e-12,
            "{file}: Jacobian differs by {worst_jacobian}"
        );
    }
}

#[test]
fn k_sees_the_same_joints_in_the_same_order() {
    for (file, text, tip) in ARMS {
        let (ours, theirs) = both_chains(file, text, tip);
        let k_names: Vec<String> = theirs.iter_joints().map(|j| j.name.clone()).collect();
        assert_eq!(ours.joint_names(), k_names, "{file}");
    }
}
