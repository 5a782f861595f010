//! The `fairgrasp` binary end to end: JSON shapes, exit codes, and error messages.

use fairgrasp_kinematics::fairino::FR3_ZERO_FLANGE_XYZ;
use serde_json::Value;

mod common;
use common::{fairgrasp, tiny_recipe, train};

fn json(args: &[&str]) -> (Value, i32) {
    let out = fairgrasp(args);
    let text = String::from_utf8(out.stdout).unwrap();
    let value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{args:?}: {e}: {text}"));
    (value, out.status.code().unwrap())
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn fk_json_gives_fairinos_zero_pose_flange() {
    let (v, code) = json(&[
        "fk", "--model", "fr3", "--joints", "0", "0", "0", "0", "0", "0", "--json",
    ]);
    assert_eq!(code, 0);
    let xyz = floats(&v["flange"]["xyz"]);
    for (a, b) in xyz.iter().zip(FR3_ZERO_FLANGE_XYZ) {
        assert!((a - b).abs() < 1e-12, "{xyz:?}");
    }
    assert_eq!(floats(&v["tcp"]["quat_xyzw"]).len(), 4);
}

#[test]
fn degrees_and_radians_give_the_same_pose() {
    let (deg, _) = json(&[
        "fk", "--joints", "10", "-90", "80", "-60", "45", "0", "--deg", "--json",
    ]);
    let rad: Vec<String> = [10.0f64, -90.0, 80.0, -60.0, 45.0, 0.0]
        .iter()
        .map(|d| d.to_radians().to_string())
        .collect();
    let mut args = vec!["fk", "--json", "--joints"];
    args.extend(rad.iter().map(String::as_str));
    let (rad, _) = json(&args);
    let (a, b) = (floats(&deg["tcp"]["xyz"]), floats(&rad["tcp"]["xyz"]));
    assert!(
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12),
        "{a:?} {b:?}"
    );
}

#[test]
fn ik_json_lists_every_branch_with_its_fk_error_and_finds_the_fk_joints_again() {
    let q = [0.3, -1.2, 1.1, -1.4, 0.8, 0.5];
    let (fk, _) = json(&[
        "fk", "--json", "--joints", "0.3", "-1.2", "1.1", "-1.4", "0.8", "0.5",
    ]);
    let xyz = floats(&fk["flange"]["xyz"]);
    let rpy = floats(&fk["flange"]["rpy"]);
    let pose: Vec<String> = xyz.iter().chain(&rpy).map(|v| v.to_string()).collect();
    let mut args = vec!["ik", "--json", "--qp", "--pose"];
    args.extend(pose.iter().map(String::as_str));
    let (v, code) = json(&args);
    assert_eq!(code, 0);
    let solutions = v["solutions"].as_array().unwrap();
    assert!(!solutions.is_empty() && solutions.len() <= 8);
    let mut found = false;
    for s in solutions {
        assert!(s["fk_error_m"].as_f64().unwrap() < 1e-9);
        assert!(s["in_limits"].is_boolean());
        let joints = floats(&s["joints"]);
        found |= joints.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9);
    }
    assert!(found, "the FK joints are one of the branches");
    assert_eq!(v["qp"]["converged"], Value::Bool(true));
    assert!(v["qp"]["fk_error_m"].as_f64().unwrap() <= 1e-4);
}

#[test]
fn ik_of_an_unreachable_pose_exits_1_with_the_reason() {
    let (v, code) = json(&["ik", "--json", "--pose", "1", "1", "1", "0", "0", "0"]);
    assert_eq!(code, 1);
    assert_eq!(v["solutions"].as_array().unwrap().len(), 0);
    assert!(v["error"].as_str().unwrap().contains("out of reach"), "{v}");
    let out = fairgrasp(&["ik", "--pose", "1", "1", "1", "0", "0", "0"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stdout).contains("out of reach"));
}

#[test]
fn frames_shows_that_subtracting_positions_is_wrong_for_a_rotated_base() {
    let (v, code) = json(&[
        "frames", "--json", "--base", "0.5", "0.2", "0.75", "0", "0", "90", "--deg", "--point",
        "0.5", "0.6", "0.775",
    ]);
    assert_eq!(code, 0);
    let right = floats(&v["point_base"]);
    assert!(
        (right[0] - 0.4).abs() < 1e-12 && right[1].abs() < 1e-12,
        "{right:?}"
    );
    assert!(v["naive_error_m"].as_f64().unwrap() > 0.5);
    assert!(v["zero_pose"]["flange_error_m"].as_f64().unwrap() < 1e-12);
}

#[test]
fn joints_lists_the_fr3_joints_and_the_chain() {
    let (v, code) = json(&["joints", "--json"]);
    assert_eq!(code, 0);
    let names: Vec<&str> = v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["name"].as_str().unwrap())
        .collect();
    assert_eq!(&names[..6], ["j1", "j2", "j3", "j4", "j5", "j6"]);
    assert_eq!(v["chain"]["tip"], "tcp");
}

#[test]
fn joints_with_a_bad_urdf_names_the_file_and_the_value() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("broken.urdf");
    let text = fairgrasp_kinematics::FR3_URDF.replace(
        r#"<origin xyz="-0.28 0 0""#,
        r#"<origin xyz="-0.28 zero 0""#,
    );
    std::fs::write(&path, text).unwrap();
    let out = fairgrasp(&["joints", "--urdf", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr.contains("broken.urdf")
            && stderr.contains("joint 'j3' <origin> xyz=\"-0.28 zero 0\""),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_wrong_number_of_joints_is_a_usage_error() {
    let out = fairgrasp(&["fk", "--joints", "0", "0", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--joints"));
}

#[test]
fn bench_env_json_follows_the_flags_and_the_preset_and_its_rates_agree_with_its_times() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-bench-env");
    std::fs::create_dir_all(&dir).unwrap();
    let preset = dir.join("ten_substeps.toml");
    std::fs::write(&preset, "[physics]\nsubsteps = 10\n").unwrap();
    let (v, code) = json(&[
        "bench",
        "env",
        "--preset",
        preset.to_str().unwrap(),
        "--arm",
        "multibody",
        "--envs-per-thread",
        "3",
        "--steps",
        "20",
        "--resets",
        "5",
        "--json",
    ]);
    assert_eq!(code, 0, "{v}");
    let f = |key: &str| {
        v[key]
            .as_f64()
            .unwrap_or_else(|| panic!("{key} missing: {v}"))
    };
    assert_eq!(v["arm"], "multibody", "{v}");
    assert_eq!((f("threads"), f("envs")), (1.0, 3.0), "{v}");
    assert_eq!(f("env_steps"), 60.0, "1 thread × 3 envs × 20 steps");
    assert_eq!(
        f("substeps"),
        10.0,
        "the preset's substeps, not the default 20"
    );
    // The multibody arm always simulates: every env step ran its 10 physics steps.
    assert_eq!(f("simulated_share"), 1.0, "{v}");
    assert!(
        (f("physics_steps_per_s") / f("env_steps_per_s") - 10.0).abs() < 1e-9,
        "{v}"
    );
    assert!(
        (f("env_steps_per_s") * f("wall_s") - 60.0).abs() < 1e-6,
        "{v}"
    );
    assert!(
        (f("env_steps_per_cpu_s") * f("cpu_s") - 60.0).abs() < 1e-6,
        "{v}"
    );
    // The fastest reset of each kind is reported and no slower than its mean (which kind is
    // faster is a benchmark's question: timings on this shared machine are noisy).
    for kind in ["soft", "hard"] {
        let (min, mean) = (
            f(&format!("{kind}_reset_min_ms")),
            f(&format!("{kind}_reset_ms")),
        );
        assert!(min > 0.0 && min <= mean, "{v}");
    }
}

#[test]
fn baseline_json_has_the_rate_its_interval_and_the_outcomes_and_records_trajectories() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-cli-baseline-{}", std::process::id()));
    let (v, code) = json(&[
        "baseline",
        "--preset",
        "fixed",
        "--episodes",
        "3",
        "--json",
        "--record",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    assert_eq!(v["episodes"], 3);
    let (rate, low, high) = (
        v["success_rate"].as_f64().unwrap(),
        v["ci_low"].as_f64().unwrap(),
        v["ci_high"].as_f64().unwrap(),
    );
    assert!(low <= rate && rate <= high && (0.0..=1.0).contains(&low) && high <= 1.0);
    let total: u64 = v["outcomes"]
        .as_object()
        .unwrap()
        .values()
        .map(|n| n.as_u64().unwrap())
        .sum();
    assert_eq!(total, 3);
    for i in 0..3 {
        assert!(dir.join(format!("episode_{i:04}.csv")).exists());
        assert!(dir.join(format!("episode_{i:04}.json")).exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unknown_preset_is_refused_with_the_choices() {
    let out = fairgrasp(&["baseline", "--preset", "easy", "--episodes", "1"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("fixed, sector, wide, full, hard"),
        "{stderr}"
    );
}

#[test]
fn compare_refuses_a_thread_count_outside_1_to_256_before_writing() {
    let out_dir =
        std::env::temp_dir().join(format!("fairgrasp-cli-threads-{}", std::process::id()));
    for threads in ["0", "257"] {
        let out = fairgrasp(&[
            "compare",
            "--episodes",
            "1",
            "--threads",
            threads,
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        // Refused where the flag is parsed (clap's usage error, exit code 2), naming it and
        // the range.
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("--threads") && stderr.contains("1..=256"),
            "{stderr}"
        );
        assert!(!out_dir.exists());
    }
}

#[test]
fn train_writes_a_run_folder_and_eval_reads_its_checkpoint() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-cli-train-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (config, run) = tiny_recipe(&dir, "fixed", 64);
    let out = train(&config, &run);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in [
        "config.toml",
        "metrics.csv",
        "eval.json",
        "checkpoints/latest/meta.json",
        "checkpoints/best/model.bpk",
    ] {
        assert!(run.join(file).exists(), "{file} missing");
    }
    // A second train into the same folder without --resume is refused.
    let again = fairgrasp(&[
        "train",
        "--config",
        config.to_str().unwrap(),
        "--run-dir",
        run.to_str().unwrap(),
    ]);
    assert_eq!(again.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&again.stderr).contains("--resume"));
    let policy = run.join("checkpoints/latest");
    let (v, code) = json(&[
        "eval",
        "--policy",
        policy.to_str().unwrap(),
        "--preset",
        "fixed",
        "--episodes",
        "2",
        "--json",
    ]);
    assert_eq!(code, 0);
    for key in ["success_rate", "ci_low", "ci_high", "episodes"] {
        assert!(v.get(key).is_some(), "{key} missing: {v}");
    }
    let out = fairgrasp(&["eval", "--policy", dir.to_str().unwrap(), "--episodes", "1"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("meta.json"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn scene_finds_no_collision_at_reset_and_flags_a_cube_spawned_inside_the_base() {
    let (v, code) = json(&["scene", "--preset", "sector", "--seeds", "20", "--json"]);
    assert_eq!(code, 0, "{v}");
    assert!(v["refused"].is_null());
    assert_eq!(v["bad_starts"].as_array().unwrap().len(), 0);
    // The only contact of a clean start is the cube resting on the table, barely moved.
    let contacts = v["contacts"].as_array().unwrap();
    assert!(
        contacts
            .iter()
            .all(|c| c["verdict"] != "COLLISION (counted)"),
        "{v}"
    );
    assert!(v["object_pushed_m"].as_f64().unwrap() < 0.001, "{v}");
    // Neighbouring capsules overlap at home, and every such pair is ignored.
    let overlaps = v["capsule_overlaps_at_home"].as_array().unwrap();
    assert!(!overlaps.is_empty());
    assert!(overlaps.iter().all(|o| o["ignored"] == true), "{v}");

    let config = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/configs/pitfall1_spawn_touching.toml");
    let (v, code) = json(&["scene", "--preset", config.to_str().unwrap(), "--json"]);
    assert_eq!(code, 1, "{v}");
    assert!(
        v["refused"]
            .as_str()
            .unwrap()
            .contains("scene.cube_xy [0.07, 0.0]"),
        "{v}"
    );
    // Spawned inside the base housing, the cube is pushed out by more than a centimetre.
    assert!(v["object_pushed_m"].as_f64().unwrap() > 0.01, "{v}");
    assert!(
        v["contacts"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["a"] == "cube" && c["b"] == "base_link"
                || c["b"] == "cube" && c["a"] == "base_link"),
        "{v}"
    );
}
