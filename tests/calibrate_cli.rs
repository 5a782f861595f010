//! `fairgrasp calibrate` end to end on the example tables shipped in `assets/calibration/`
//! (made from a known mount and camera with measurement noise): the answers within the bounds
//! of `kinematics/tests/calibrate.rs`, the mount file usable as an env config and never written
//! over, and bad tables refused naming the file, the line or the problem.

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use fairgrasp_kinematics::Pose;
use serde_json::Value;

mod common;
use common::fairgrasp;

fn json(args: &[&str]) -> Value {
    let out = fairgrasp(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn pose(record: &Value) -> Pose {
    let f = |k: &str| -> Vec<f64> {
        record[k]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let (xyz, rpy) = (f("xyz"), f("rpy"));
    Pose::from_xyz_rpy([xyz[0], xyz[1], xyz[2]], [rpy[0], rpy[1], rpy[2]])
}

/// The mount `assets/calibration/touches_example.csv` was made from, as its comment and the docs
/// write it (1.5708, not π/2).
#[allow(clippy::approx_constant)]
fn example_mount() -> Pose {
    Pose::from_xyz_rpy([0.2, -0.1, 0.75], [0.0, 0.1745, 1.5708])
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_example_touches_give_the_mount_they_were_made_from() {
    let v = json(&[
        "calibrate",
        "points",
        "assets/calibration/touches_example.csv",
        "--json",
    ]);
    let truth = example_mount();
    let (dp, dr) = pose(&v["base_in_world"]).distance_to(&truth);
    assert!(dp < 0.002 && dr < 0.3f64.to_radians(), "{dp} m, {dr} rad");
    assert_eq!(v["points"], 6);
    assert!(v["rms_m"].as_f64().unwrap() < 0.001, "{v}");
    assert!(v["env_refuses"].is_null(), "{v}");
}

#[test]
fn the_mount_file_loads_as_an_env_config_and_is_never_written_over() {
    let dir = scratch("calibrate-out");
    let out = dir.join("my_cell.toml");
    let out_arg = out.to_str().unwrap();
    let file = "assets/calibration/touches_example.csv";
    let first = fairgrasp(&["calibrate", "points", file, "--out", out_arg]);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let config = EnvConfig::from_toml_file(&out).unwrap();
    let (dp, dr) =
        Pose::from_xyz_rpy(config.arm.base_xyz, config.arm.base_rpy).distance_to(&example_mount());
    assert!(dp < 0.002 && dr < 0.005, "{dp} {dr}");

    std::fs::write(&out, "# mine\n").unwrap();
    let second = fairgrasp(&["calibrate", "points", file, "--out", out_arg]);
    assert!(!second.status.success());
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(
        err.contains("already exists") && err.contains("my_cell.toml"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "# mine\n");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_example_stations_give_the_camera_they_were_made_from() {
    let v = json(&[
        "calibrate",
        "hand-eye",
        "assets/calibration/camera_stations_example.csv",
        "--json",
    ]);
    let truth = Pose::from_xyz_rpy([0.9, -0.3, 0.7], [-2.4, 0.0, 2.2]);
    let (dp, dr) = pose(&v["camera_in_base"]).distance_to(&truth);
    assert!(dp < 0.003 && dr < 0.3f64.to_radians(), "{dp} m, {dr} rad");
    assert!(v["method"].as_str().unwrap().contains("Park"));
    assert_eq!(v["position_residuals_m"].as_array().unwrap().len(), 8);
}

#[test]
fn bad_tables_are_refused_naming_the_problem() {
    let dir = scratch("calibrate-bad");
    let cases: [(&str, &str, &[&str]); 5] = [
        (
            "two.csv",
            "world_x_m,world_y_m,world_z_m,tcp_x_m,tcp_y_m,tcp_z_m\n1,0,0,1,0,0\n0,1,0,0,1,0\n",
            &["2 point pairs", "at least 3"],
        ),
        (
            "line.csv",
            "world_x_m,world_y_m,world_z_m,tcp_x_m,tcp_y_m,tcp_z_m\n1,0,0,1,0,0\n2,0,0,2,0,0\n3,0,0,3,0,0\n",
            &["one line"],
        ),
        (
            "units.csv",
            "world_x,world_y_m\n1,2\n",
            &["units.csv:1", "no unit"],
        ),
        (
            "cell.csv",
            "world_x_m,world_y_m,world_z_m,tcp_x_m,tcp_y_m,tcp_z_m\n1,0,0,1,0,0\n2,0,zero,2,0,0\n",
            &["cell.csv:3", "world_z", "zero"],
        ),
        (
            "notcp.csv",
            "world_x_m,world_y_m,world_z_m\n1,0,0\n",
            &["TCP is missing"],
        ),
    ];
    for (name, text, needles) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = fairgrasp(&["calibrate", "points", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        for n in needles {
            assert!(err.contains(n), "{name}: `{n}` not in: {err}");
        }
        assert!(!err.contains("panicked"), "{err}");
    }
    // A folder is refused before anything is read.
    let out = fairgrasp(&["calibrate", "points", dir.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("not a regular file"));
    std::fs::remove_dir_all(&dir).ok();
}
