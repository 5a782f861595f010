//! `fairgrasp export` and `fairgrasp playback` from the command line: the three formats agree
//! sample for sample, every step is ≤ 1°, the JSON's `period_sec` / `joints_deg` are the ROS 2
//! driver's goal, a played export still grasps, and what must be refused is refused (a file
//! that crosses a limit, an existing `--out`, a period out of range, a failed episode, a stream
//! written with `--no-gripper`) with nothing written or played; the gripper's commands are
//! written by default.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod common;
use common::{fairgrasp_in, stderr, stdout};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-export-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The rows of an N×6 float64 `.npy` file written by `export`.
fn read_npy(path: &Path) -> Vec<[f64; 6]> {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + len]).unwrap();
    assert!(header.contains("'descr': '<f8'") && header.contains("'fortran_order': False"));
    assert_eq!((10 + len) % 64, 0, "the header is padded to 64 bytes");
    let data: Vec<f64> = bytes[10 + len..]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert!(
        header.contains(&format!("'shape': ({}, 6)", data.len() / 6)),
        "{header}"
    );
    data.chunks(6).map(|r| r.try_into().unwrap()).collect()
}

#[test]
fn the_three_formats_agree_and_a_played_export_still_grasps() {
    let dir = temp_dir("formats");
    let base = [
        "export",
        "--preset",
        "full",
        "--episode",
        "2",
        "--method",
        "oracle",
        "--gripper",
    ];
    for out in ["s.json", "s.csv", "s.npy"] {
        let o = fairgrasp_in(&dir, &[&base[..], &["--out", out]].concat());
        assert!(o.status.success(), "{out}: {}", stderr(&o));
    }
    let doc: Value = serde_json::from_slice(&std::fs::read(dir.join("s.json")).unwrap()).unwrap();
    assert_eq!(doc["period_sec"], 0.008);
    let flat: Vec<f64> = doc["joints_deg"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let json: Vec<[f64; 6]> = flat.chunks(6).map(|r| r.try_into().unwrap()).collect();
    assert_eq!(doc["samples"].as_u64().unwrap() as usize, json.len());
    assert_eq!(doc["source"]["outcome"], "success");
    let csv_text = std::fs::read_to_string(dir.join("s.csv")).unwrap();
    let csv: Vec<[f64; 6]> = csv_text
        .lines()
        .skip(1)
        .map(|l| {
            let cells: Vec<f64> = l.split(',').map(|c| c.parse().unwrap()).collect();
            cells[2..8].try_into().unwrap()
        })
        .collect();
    let npy = read_npy(&dir.join("s.npy"));
    assert_eq!((csv.len(), npy.len()), (json.len(), json.len()));
    for n in 0..json.len() {
        for i in 0..6 {
            assert!(
                (csv[n][i] - json[n][i]).abs() < 1e-8 && npy[n][i] == json[n][i],
                "sample {n}"
            );
            if n > 0 {
                assert!(
                    (json[n][i] - json[n - 1][i]).abs() <= 1.0,
                    "sample {n} j{}",
                    i + 1
                );
            }
        }
    }
    // The gripper: closed somewhere after the start in all three.
    let closes = doc["gripper"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["command"] == 1.0)
        .unwrap();
    let at = closes["sample"].as_u64().unwrap() as usize;
    let column = |n: usize| {
        csv_text
            .lines()
            .nth(n + 1)
            .unwrap()
            .rsplit(',')
            .next()
            .unwrap()
            .to_string()
    };
    assert_eq!((column(at - 1).as_str(), column(at).as_str()), ("-1", "1"));
    let gripper = std::fs::read(dir.join("s.gripper.npy")).unwrap();
    assert_eq!(
        (gripper.len() - 8 * json.len()) % 64,
        0,
        "one command per sample after the header"
    );
    assert!(gripper.len() - 8 * json.len() <= 128);
    for file in ["s.json", "s.csv"] {
        let mut args = vec!["playback", file, "--json"];
        if file.ends_with(".csv") {
            args.extend(["--preset", "full", "--episode", "2"]);
        }
        let o = fairgrasp_in(&dir, &args);
        assert!(o.status.success(), "{file}: {}{}", stdout(&o), stderr(&o));
        let report: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
        assert_eq!(report["outcome"], "success", "{file}: {report}");
        assert!(
            report["max_tracking_error_deg"].as_f64().unwrap() < 0.5,
            "{report}"
        );
    }
}

#[test]
fn the_real_cells_mount_and_a_placed_cube_travel_with_the_file_to_playback() {
    let dir = temp_dir("cell");
    // A base tilted 10° and turned 90° (degrees on the command line, radians in the file).
    let mount = ["--base", "0.2", "-0.1", "0.75", "0", "10", "90", "--deg"];
    let o = fairgrasp_in(
        &dir,
        &[&["export", "--gripper", "--out", "b.json"][..], &mount].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: Value = serde_json::from_slice(&std::fs::read(dir.join("b.json")).unwrap()).unwrap();
    let base: Vec<f64> = serde_json::from_value(doc["source"]["base_in_world"].clone()).unwrap();
    assert!(
        (base[4] - 10f64.to_radians()).abs() < 1e-12
            && (base[5] - 90f64.to_radians()).abs() < 1e-12
    );
    // Played without flags: the mount comes from the file, in radians, so it grasps again.
    for deg in [&[][..], &["--deg"][..]] {
        let o = fairgrasp_in(&dir, &[&["playback", "b.json", "--json"][..], deg].concat());
        let report: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
        assert_eq!(report["outcome"], "success", "{report}");
        assert_eq!(report["steps"], doc["source"]["steps"]);
    }
    // The same episode on the preset's own level mount is another motion (other steps): the
    // mount is what makes the joints right for the real cell.
    let o = fairgrasp_in(&dir, &["export", "--gripper", "--out", "level.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let level: Value =
        serde_json::from_slice(&std::fs::read(dir.join("level.json")).unwrap()).unwrap();
    assert_ne!(level["source"]["steps"], doc["source"]["steps"]);
    // A cube placed by hand (table frame, yaw 30°).
    let cube = ["--cube", "0.35", "0.05", "30", "--deg"];
    let o = fairgrasp_in(
        &dir,
        &[&["export", "--gripper", "--out", "c.json"][..], &cube].concat(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let c: Value = serde_json::from_slice(&std::fs::read(dir.join("c.json")).unwrap()).unwrap();
    assert_eq!(c["source"]["cube"]["xy_m"], serde_json::json!([0.35, 0.05]));
    let o = fairgrasp_in(&dir, &["playback", "c.json", "--json"]);
    let report: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    assert_eq!(report["outcome"], "success", "{report}");
    // A mount the env refuses is named.
    let bad = [
        "export", "--out", "x.json", "--base", "0.2", "-0.1", "0.75", "3.14", "0", "0",
    ];
    let o = fairgrasp_in(&dir, &bad);
    assert!(
        !o.status.success() && stderr(&o).contains("arm.base_rpy"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("x.json").exists());
}

#[test]
fn what_must_not_reach_a_controller_is_refused_and_nothing_is_written() {
    let dir = temp_dir("refusals");
    let o = fairgrasp_in(&dir, &["export", "--gripper", "--out", "ok.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let original = std::fs::read(dir.join("ok.json")).unwrap();
    // A 2° jump of j3 at sample 100: refused by playback, naming sample and joint.
    let mut doc: Value = serde_json::from_slice(&original).unwrap();
    let v = doc["joints_deg"][100 * 6 + 2].as_f64().unwrap();
    doc["joints_deg"][100 * 6 + 2] = (v + 2.0).into();
    std::fs::write(dir.join("jump.json"), serde_json::to_vec(&doc).unwrap()).unwrap();
    let o = fairgrasp_in(&dir, &["playback", "jump.json"]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("sample 100") && e.contains("j3"),
        "{e}"
    );
    assert!(
        e.contains("1.00° per sample") && e.contains("not played"),
        "{e}"
    );
    // An existing --out is never replaced.
    let o = fairgrasp_in(
        &dir,
        &["export", "--gripper", "--episode", "1", "--out", "ok.json"],
    );
    assert!(
        !o.status.success() && stderr(&o).contains("never replaced"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(dir.join("ok.json")).unwrap(), original);
    // Periods outside 1–16 ms and unknown extensions.
    for (args, says) in [
        (&["--period", "0.02", "--out", "a.json"][..], "0.001–0.016"),
        (
            &["--period", "0.0005", "--out", "a.json"][..],
            "0.001–0.016",
        ),
        (&["--out", "a.txt"][..], ".json, .csv or .npy"),
    ] {
        let o = fairgrasp_in(&dir, &[&["export"][..], args].concat());
        assert!(
            !o.status.success() && stderr(&o).contains(says),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    // A failed episode (the open-loop script on `hard` #1 stops against the cube) is refused
    // unless asked for.
    let failed = [
        "export",
        "--preset",
        "hard",
        "--episode",
        "1",
        "--out",
        "f.json",
    ];
    let o = fairgrasp_in(&dir, &failed);
    assert!(
        !o.status.success() && stderr(&o).contains("--allow-failure"),
        "{}",
        stderr(&o)
    );
    let o = fairgrasp_in(&dir, &[&failed[..], &["--allow-failure"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    // Without gripper commands playback cannot grasp; a CSV must say where it plays.
    let o = fairgrasp_in(&dir, &["export", "--no-gripper", "--out", "arm_only.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = fairgrasp_in(&dir, &["playback", "arm_only.json"]);
    assert!(
        !o.status.success() && stderr(&o).contains("--no-gripper"),
        "{}",
        stderr(&o)
    );
    let o = fairgrasp_in(&dir, &["export", "--gripper", "--out", "s.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = fairgrasp_in(&dir, &["playback", "s.csv"]);
    assert!(
        !o.status.success() && stderr(&o).contains("--preset and --episode"),
        "{}",
        stderr(&o)
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["arm_only.json", "f.json", "jump.json", "ok.json", "s.csv"]
    );
}

#[test]
fn export_writes_the_gripper_by_default_so_playback_grasps_and_no_gripper_leaves_it_out() {
    let dir = temp_dir("default-gripper");
    let o = fairgrasp_in(&dir, &["export", "--out", "plain.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: Value =
        serde_json::from_slice(&std::fs::read(dir.join("plain.json")).unwrap()).unwrap();
    // The grasp closes the gripper at least once (command +1 closed).
    let events = doc["gripper"].as_array().expect("a gripper list");
    assert!(events.iter().any(|e| e["command"] == 1.0), "{doc}");
    let o = fairgrasp_in(&dir, &["playback", "plain.json", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let played: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(played["outcome"], "success", "{played}");
    // The old flag still runs and changes nothing.
    let o = fairgrasp_in(&dir, &["export", "--gripper", "--out", "old.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read(dir.join("old.json")).unwrap(),
        std::fs::read(dir.join("plain.json")).unwrap()
    );
    // .npy: the gripper's commands beside the joints, unless --no-gripper.
    let o = fairgrasp_in(&dir, &["export", "--out", "plain.npy"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("plain.gripper.npy").is_file());
    let o = fairgrasp_in(&dir, &["export", "--no-gripper", "--out", "arm.npy"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.join("arm.gripper.npy").exists());
    let o = fairgrasp_in(&dir, &["export", "--no-gripper", "--out", "arm.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: Value = serde_json::from_slice(&std::fs::read(dir.join("arm.json")).unwrap()).unwrap();
    assert!(doc["gripper"].as_array().is_none_or(Vec::is_empty), "{doc}");
    let o = fairgrasp_in(&dir, &["playback", "arm.json"]);
    assert!(
        !o.status.success() && stderr(&o).contains("no gripper commands"),
        "{}",
        stderr(&o)
    );
    let o = fairgrasp_in(
        &dir,
        &["export", "--gripper", "--no-gripper", "--out", "both.json"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!dir.join("both.json").exists());
    std::fs::remove_dir_all(&dir).ok();
}
