//! `--policy` means the same in every command that runs a policy (`eval`, `export`, `replay`):
//! a shipped policy's name, its policy folder (as in `assets/policies/`), its checkpoint folder,
//! or a run folder (whose `checkpoints/best` is used); the four give the same episodes. `eval`
//! used to take only the checkpoint folder ("no meta.json here").

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;

mod common;
use common::fairgrasp;

fn ok(o: &Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

#[test]
fn eval_export_and_replay_take_a_policy_by_name_policy_folder_checkpoint_or_run_folder() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("policy-arg");
    std::fs::remove_dir_all(&dir).ok();
    // A run folder as `fairgrasp train` leaves it: the checkpoint under checkpoints/best.
    let run = dir.join("run");
    copy_dir(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/policies/residual_nudged/checkpoint"),
        &run.join("checkpoints/best"),
    );
    let forms = [
        "residual_nudged".to_string(),
        "assets/policies/residual_nudged".to_string(),
        "assets/policies/residual_nudged/checkpoint".to_string(),
        run.display().to_string(),
    ];
    let mut evals = Vec::new();
    let mut exports = Vec::new();
    for (k, policy) in forms.iter().enumerate() {
        let common = ["--policy", policy.as_str(), "--preset", "nudged"];
        let o = fairgrasp(&[&["eval"][..], &common, &["--episodes", "3", "--json"]].concat());
        ok(&o, &format!("eval --policy {policy}"));
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        evals.push((v["outcomes"].clone(), v["mean_return"].clone()));

        let json = dir.join(format!("export{k}.json"));
        let o = fairgrasp(&[&["export"][..], &common, &["--out", json.to_str().unwrap()]].concat());
        ok(&o, &format!("export --policy {policy}"));
        let doc: Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
        exports.push(doc["joints_deg"].clone());

        let html = dir.join(format!("replay{k}.html"));
        let o = fairgrasp(&[&["replay"][..], &common, &["--out", html.to_str().unwrap()]].concat());
        ok(&o, &format!("replay --policy {policy}"));
        assert!(html.is_file());
    }
    // The same outcomes and mean return on three episodes, the same exported joints: the same
    // weights ran, whichever way they were named.
    assert!(evals[0].1.as_f64().is_some(), "{:?}", evals[0]);
    for k in 1..forms.len() {
        assert_eq!(evals[k], evals[0], "{} against {}", forms[k], forms[0]);
        assert_eq!(exports[k], exports[0], "{} against {}", forms[k], forms[0]);
    }
    // What is none of the four is refused, naming them.
    let o = fairgrasp(&["eval", "--policy", "assets/policies", "--episodes", "1"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("shipped policy") && e.contains("run folder") && e.contains("residual_nudged"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
