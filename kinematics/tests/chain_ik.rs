//! IK for any serial chain of a URDF: the Jacobian matches finite differences; random reachable
//! poses of a 7-joint arm, the FR5 and the FR3 (read from their URDFs) are solved within the
//! tolerances from random starts, never outside the joint limits; a tip other than the last
//! link works; bad requests are refused; the same seed gives the same answer.

use fairgrasp_kinematics::chain_ik::{ChainIk, ChainIkError, ChainIkOptions};
use fairgrasp_kinematics::{Pose, UrdfRobot};

fn chain(file: &str, tip: Option<&str>) -> ChainIk {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(file);
    ChainIk::new(&UrdfRobot::from_file(path).unwrap(), tip).unwrap()
}

#[test]
fn the_jacobian_is_the_derivative_of_the_tips_pose() {
    for (file, tip) in [
        ("seven_joint_arm.urdf", None),
        ("fr5.urdf", None),
        ("seven_joint_arm.urdf", Some("link5")),
    ] {
        let ik = chain(file, tip);
        for seed in 0..20 {
            let q = ik.random_joints(seed);
            let (pose, jacobian) = ik.chain.fk_jacobian(&q);
            assert!((pose.xyz()[0] - ik.chain.fk(&q).xyz()[0]).abs() < 1e-12);
            for c in 0..ik.dof() {
                let h = 1e-6;
                let mut qh = q.clone();
                qh[c] += h;
                let moved = ik.chain.fk(&qh);
                let dp: Vec<f64> = (0..3)
                    .map(|r| (moved.xyz()[r] - pose.xyz()[r]) / h)
                    .collect();
                let dr = (moved.iso.rotation * pose.iso.rotation.inverse()).scaled_axis() / h;
                for r in 0..3 {
                    assert!(
                        (jacobian[(r, c)] - dp[r]).abs() < 1e-5,
                        "{file} linear ({r}, {c})"
                    );
                    assert!(
                        (jacobian[(r + 3, c)] - dr[r]).abs() < 1e-5,
                        "{file} angular ({r}, {c})"
                    );
                }
            }
        }
    }
}

/// Solves `n` random reachable poses (FK of a random configuration) from another random start;
/// returns the successes, checking every answer's limits and error.
fn solve_random(ik: &ChainIk, n: u64) -> usize {
    let options = ChainIkOptions::default();
    let mut solved = 0;
    for k in 0..n {
        let target = ik.chain.fk(&ik.random_joints(2 * k + 1_000_000));
        let start = ik.random_joints(2 * k + 1);
        let Ok(s) = ik.solve(&target, &start, &ChainIkOptions { seed: k, ..options }) else {
            continue;
        };
        for (i, v) in s.joints.iter().enumerate() {
            assert!(
                *v >= ik.lower[i] && *v <= ik.upper[i],
                "joint {i} = {v} outside its limits"
            );
        }
        let reached = ik.chain.fk(&s.joints);
        let (dp, dr) = reached.distance_to(&target);
        assert!(
            dp <= options.position_tolerance * 1.0001
                && dr <= options.orientation_tolerance * 1.0001
        );
        solved += 1;
    }
    solved
}

#[test]
fn random_reachable_poses_of_a_seven_joint_arm_the_fr5_and_the_fr3_are_solved() {
    let arms = [
        ("seven_joint_arm.urdf", None),
        ("fr5.urdf", None),
        ("fr3.urdf", Some("tool0")),
    ];
    for (file, tip) in arms {
        let (ik, n) = (chain(file, tip), 500);
        let solved = solve_random(&ik, n);
        println!("{file}: {solved}/{n} random reachable poses solved");
        assert!(solved as f64 >= 0.99 * n as f64, "{file}: {solved}/{n}");
    }
}

#[test]
fn a_tip_before_the_last_link_is_a_shorter_chain() {
    let ik = chain("seven_joint_arm.urdf", Some("link6"));
    assert_eq!(ik.dof(), 6);
    assert_eq!(ik.names, ["a1", "a2", "a3", "a4", "a5", "a6"]);
    assert!(solve_random(&ik, 100) >= 99);
}

#[test]
fn bad_requests_are_refused_and_the_same_seed_gives_the_same_answer() {
    let ik = chain("seven_joint_arm.urdf", None);
    let target = ik.chain.fk(&ik.random_joints(7));
    let o = ChainIkOptions::default();
    let e = ik.solve(&target, &[0.0; 6], &o).unwrap_err();
    assert!(
        matches!(
            e,
            ChainIkError::StartLength {
                expected: 7,
                got: 6,
                ..
            }
        ),
        "{e}"
    );
    let e = ik
        .solve(&target, &[0.0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.0], &o)
        .unwrap_err();
    assert!(e.to_string().contains("`a2` = 3.0000"), "{e}");
    let e = ik.solve(&target, &[f64::NAN; 7], &o).unwrap_err();
    assert_eq!(e, ChainIkError::NonFinite);
    // 3 m away: out of reach, the best attempt is reported.
    let far = Pose::from_xyz([3.0, 0.0, 0.5]);
    let quick = ChainIkOptions {
        max_attempts: 5,
        ..o
    };
    let e = ik.solve(&far, &[0.0; 7], &quick).unwrap_err();
    let ChainIkError::NotConverged {
        position_error_m,
        attempts,
        ..
    } = e
    else {
        panic!("{e}")
    };
    assert!(
        position_error_m > 1.7 && attempts == 5,
        "{position_error_m}"
    );
    let start = ik.random_joints(8);
    let a = ik
        .solve(&target, &start, &ChainIkOptions { seed: 3, ..o })
        .unwrap();
    let b = ik
        .solve(&target, &start, &ChainIkOptions { seed: 3, ..o })
        .unwrap();
    assert_eq!(a, b);
}
