//! `fk --urdf` and `ik --urdf` on any serial arm: the 7-joint arm stretched upright reaches the
//! sum of its link offsets; `ik` answers a pose `fk` gave, and `fk` of that answer lands on it;
//! a branching URDF needs `--tip`; a wrong number of joints names the chain's joints; `--joints`
//! and `--current` take as many values as the chain has joints, flags after them included, and
//! `--qp` is accepted (the chain IK is a QP solver).

use std::process::Output;

use serde_json::Value;

mod common;
use common::fairgrasp;

fn json(o: &Output) -> Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

const SEVEN: &str = "assets/seven_joint_arm.urdf";

#[test]
fn fk_and_ik_of_a_seven_joint_arm_agree() {
    // Upright, every offset is along z: 0.15 + 0.19 + 0.21 + 0.19 + 0.21 + 0.19 + 0.08 + 0.05 m.
    let up = json(&fairgrasp(&[
        "fk", "--urdf", SEVEN, "--json", "--joints", "0", "0", "0", "0", "0", "0", "0",
    ]));
    let z = up["pose"]["xyz"][2].as_f64().unwrap();
    assert!((z - 1.27).abs() < 1e-12, "{z}");
    let q = ["0.3", "0.5", "-0.2", "-1.1", "0.4", "0.7", "0.1"];
    let fk = json(&fairgrasp(
        &[&["fk", "--urdf", SEVEN, "--json", "--joints"][..], &q].concat(),
    ));
    let xyz: Vec<f64> = serde_json::from_value(fk["pose"]["xyz"].clone()).unwrap();
    let rpy: Vec<f64> = serde_json::from_value(fk["pose"]["rpy"].clone()).unwrap();
    let pose: Vec<String> = xyz.iter().chain(&rpy).map(|v| format!("{v}")).collect();
    let pose: Vec<&str> = pose.iter().map(String::as_str).collect();
    let ik = json(&fairgrasp(
        &[&["ik", "--urdf", SEVEN, "--json", "--pose"][..], &pose].concat(),
    ));
    assert_eq!(ik["solution"]["converged"], true, "{ik}");
    let joints: Vec<String> = ik["solution"]["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.to_string())
        .collect();
    assert_eq!(joints.len(), 7);
    let joints: Vec<&str> = joints.iter().map(String::as_str).collect();
    let back = json(&fairgrasp(
        &[&["fk", "--urdf", SEVEN, "--json", "--joints"][..], &joints].concat(),
    ));
    for i in 0..3 {
        let d = back["pose"]["xyz"][i].as_f64().unwrap() - xyz[i];
        assert!(d.abs() < 1e-4, "xyz[{i}] off by {d}");
    }
    assert_eq!(back["in_limits"], true);
}

#[test]
fn a_branching_urdf_needs_a_tip_and_a_wrong_joint_count_names_the_joints() {
    // A six-joint chain takes --joints as the FR3 does, flags after it included.
    let fr5 = [
        "fk",
        "--urdf",
        "assets/fr5.urdf",
        "--joints",
        "0",
        "0",
        "0",
        "0",
        "0",
        "0",
        "--json",
    ];
    // The FR5's zero pose from its DH sheet (docs/FR3.md): x = a2 + a3, y = −(d4 + d6), z = d1 − d5.
    let xyz = json(&fairgrasp(&fr5))["pose"]["xyz"].clone();
    for (i, want) in [-0.425 - 0.395, -(0.102 + 0.100), 0.152 - 0.102]
        .into_iter()
        .enumerate()
    {
        assert!((xyz[i].as_f64().unwrap() - want).abs() < 1e-12, "{xyz}");
    }
    let o = fairgrasp(&[
        "ik",
        "--urdf",
        "assets/fr3.urdf",
        "--pose",
        "0.35",
        "0",
        "0.3",
        "3.14159",
        "0",
        "0",
    ]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("name a tip link"), "{e}");
    let o = fairgrasp(&[
        "ik",
        "--urdf",
        "assets/fr3.urdf",
        "--tip",
        "tool0",
        "--json",
        "--pose",
        "0.35",
        "0",
        "0.3",
        "3.14159",
        "0",
        "0",
    ]);
    assert_eq!(json(&o)["solution"]["converged"], true);
    let o = fairgrasp(&["fk", "--urdf", SEVEN, "--joints", "0", "0", "0"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("7 movable joints (a1, a2, a3, a4, a5, a6, a7), got 3"),
        "{e}"
    );
}

#[test]
fn fk_of_a_seven_joint_chain_takes_seven_joints_with_flags_after_them() {
    // `--joints` takes as many values as the chain has joints; a flag after the list ends it.
    let q = ["0", "30", "0", "-60", "0", "45", "0"];
    let after = json(&fairgrasp(
        &[
            &["fk", "--urdf", SEVEN, "--joints"][..],
            &q,
            &["--deg", "--json"],
        ]
        .concat(),
    ));
    let before = json(&fairgrasp(
        &[
            &["fk", "--urdf", SEVEN, "--deg", "--json", "--joints"][..],
            &q,
        ]
        .concat(),
    ));
    assert_eq!(after, before);
    let radians: Vec<f64> = serde_json::from_value(after["joints"].clone()).unwrap();
    assert!((radians[5] - 45f64.to_radians()).abs() < 1e-15, "{after}");
    // Upright but for a2 = 30° and a4 = −60°, a6 = 45°: the tip is off the z axis.
    assert!(after["pose"]["xyz"][0].as_f64().unwrap() > 0.3, "{after}");
    // The separate flag is gone; a wrong count for the chain is a usage error naming the joints.
    let o = fairgrasp(&[&["fk", "--urdf", SEVEN, "--chain-joints"][..], &q].concat());
    assert_eq!(o.status.code(), Some(2));
    let o = fairgrasp(&[
        "fk", "--urdf", SEVEN, "--joints", "0", "0", "0", "0", "0", "0", "--json",
    ]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("7 movable joints (a1, a2, a3, a4, a5, a6, a7), got 6"),
        "{e}"
    );
    // Without --urdf the FR3 takes six, and says what seven would need.
    let o = fairgrasp(&[&["fk", "--joints"][..], &q].concat());
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("--joints takes 6 joint angles") && e.contains("--urdf"),
        "{e}"
    );
}

#[test]
fn ik_of_a_urdf_chain_accepts_qp_and_starts_from_a_seven_value_current() {
    // The chain IK is itself the QP solver: --qp changes nothing in its answer.
    let ask = |extra: &[&str]| {
        json(&fairgrasp(
            &[
                &[
                    "ik", "--urdf", SEVEN, "--json", "--deg", "--pose", "0.4", "0.1", "0.6",
                ][..],
                &["180", "0", "0"],
                extra,
            ]
            .concat(),
        ))
    };
    let current = ["--current", "0", "10", "0", "-20", "0", "10", "0"];
    let plain = ask(&current);
    let qp = ask(&[&["--qp"][..], &current].concat());
    assert_eq!(plain["solution"]["converged"], true, "{plain}");
    assert_eq!(plain, qp);
    let start: Vec<f64> = serde_json::from_value(plain["current"].clone()).unwrap();
    assert_eq!(start.len(), 7);
    assert!((start[3] + 20f64.to_radians()).abs() < 1e-15, "{plain}");
}
