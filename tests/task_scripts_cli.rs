//! A script named on the command line is a control of the preset's task, from the planner's one
//! table of every task's controls: `replay --policy` and `export --method` run the place task's
//! scripts on a place preset, refuse another task's script naming both tasks (and write nothing),
//! and `compare` without `--policy` adds the shipped policies only on presets of the task they
//! were trained on.

use std::path::{Path, PathBuf};

use serde_json::Value;

mod common;
use common::{fairgrasp, ok, stderr};

/// A fresh folder for one test's files.
fn temp_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("task-scripts-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The method names of a replay JSON.
fn replay_methods(path: &Path) -> Vec<String> {
    let doc: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    doc["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["method"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn replay_runs_the_presets_tasks_scripts_and_refuses_another_tasks() {
    let dir = temp_dir("replay");
    let json = dir.join("place.json");
    let place = [
        "replay",
        "--preset",
        "place",
        "--policy",
        "open_loop",
        "--policy",
        "closed_loop",
        "--json",
        json.to_str().unwrap(),
    ];
    ok(&fairgrasp(&place));
    // `open_loop` and `closed_loop` are the place task's controls on a place preset.
    assert_eq!(replay_methods(&json), ["place script", "closed-loop place"]);
    let lift_json = dir.join("lift.json");
    let refused = fairgrasp(&[
        "replay",
        "--preset",
        "sector",
        "--policy",
        "force_search",
        "--json",
        lift_json.to_str().unwrap(),
    ]);
    assert!(!refused.status.success());
    let e = stderr(&refused);
    assert!(
        e.contains("`force_search` is a script of the place task")
            && e.contains("this preset's task is lift")
            && e.contains("open_loop, closed_loop, oracle, calibrated, tuned_grip"),
        "{e}"
    );
    assert!(!lift_json.exists(), "a refused replay writes nothing");
}

#[test]
fn export_takes_every_control_of_the_table_and_refuses_another_tasks() {
    let dir = temp_dir("export");
    let out = dir.join("search.json");
    let o = fairgrasp(&[
        "export",
        "--preset",
        "place",
        "--method",
        "force_search",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&o);
    let doc: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(doc["source"]["method"], "force_search");
    let refused_out = dir.join("calibrated.json");
    let refused = fairgrasp(&[
        "export",
        "--preset",
        "place",
        "--method",
        "calibrated",
        "--out",
        refused_out.to_str().unwrap(),
    ]);
    assert!(!refused.status.success());
    let e = stderr(&refused);
    assert!(
        e.contains("`calibrated` is a script of the lift task")
            && e.contains("this preset's task is place")
            && e.contains("force_search"),
        "{e}"
    );
    assert!(!refused_out.exists(), "a refused export writes nothing");
    let help = fairgrasp(&["export", "--help"]);
    let text = common::stdout(&help);
    assert!(
        text.contains("lift: open_loop, closed_loop, oracle, calibrated, tuned_grip")
            && text.contains("place: open_loop, force_search"),
        "{text}"
    );
}

/// The methods of `fairgrasp compare --preset PRESET` without `--policy`, one episode.
fn default_compare_methods(dir: &Path, preset: &str) -> Vec<String> {
    let out = dir.join(preset);
    let o = fairgrasp(&[
        "compare",
        "--preset",
        preset,
        "--episodes",
        "1",
        "--replay-episodes",
        "0",
        "--threads",
        "1",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    ok(&o);
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    doc["methods"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap().to_string())
        .collect()
}

#[test]
fn compare_adds_the_shipped_policies_only_on_the_task_they_were_trained_on() {
    let dir = temp_dir("compare");
    let lift = default_compare_methods(&dir, "sector");
    assert_eq!(
        lift[lift.len() - 2..],
        ["residual PPO: residual_generalist", "pure PPO: pure_full"]
    );
    let place = default_compare_methods(&dir, "place");
    assert_eq!(
        place,
        [
            "place script",
            "place script + force search",
            "closed-loop place",
            "closed-loop place + force search",
        ]
    );
}
