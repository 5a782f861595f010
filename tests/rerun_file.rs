//! Episodes as Rerun recordings (`python/fairgrasp/rerun.py`, tested by `python/tests-rerun`,
//! pytest): `fairgrasp replay --json` (this build's binary) records two methods on one scenario,
//! `fairgrasp.rerun.save` writes the `.rrd`, and Rerun's own reader reads it back (entities and
//! time range); and the replay JSON loader's property tests
//! (`python/tests-rerun/test_replay_json_fuzz.py`, Hypothesis, derandomized: about 1 000 cases of
//! arbitrary bytes and mutations of a real replay, plus truncated, 200 MB, gzip-bomb, FIFO,
//! folder and missing inputs, each loaded or refused naming the file, within a time and memory
//! bound). Run through `scripts/python-package-test.sh` in a venv of its own
//! (`target/python-rerun-venv`, created on the first run from `scripts/requirements-rerun.txt`:
//! rerun-sdk 0.41.0 and Hypothesis 6.155.2 beside the package's pins), with the extension `cargo
//! test --workspace` has just built. The Rust build itself has no Rerun dependency.

use std::process::Command;

mod common;

#[test]
fn an_episode_written_as_rrd_reads_back_with_rerun() {
    let out = common::pytest(Some(&common::PythonSuite {
        venv: "target/python-rerun-venv",
        requirements: "scripts/requirements-rerun.txt",
        tests: "python/tests-rerun",
    }))
    .output()
    .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "pytest failed:\n{stdout}\n{stderr}");
    assert!(
        stdout.contains("15 passed") && !stdout.contains("skipped"),
        "every Rerun test must run here:\n{stdout}"
    );
}

/// `--json` never replaces a file that is not a fairgrasp replay JSON, and writes no HTML
/// unless `--out` asks for it.
#[test]
fn replay_json_refuses_a_foreign_file_and_writes_only_the_json() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-replay-json-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let foreign = dir.join("notes.json");
    std::fs::write(&foreign, "my notes").unwrap();
    let run = |json: &std::path::Path| {
        Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
            .args(["replay", "--policy", "open_loop", "--json"])
            .arg(json)
            .current_dir(&dir)
            .output()
            .unwrap()
    };
    let refused = run(&foreign);
    assert!(!refused.status.success());
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("notes.json: the file exists and is not a fairgrasp replay JSON"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&foreign).unwrap(), "my notes");
    let written = dir.join("episode.json");
    assert!(run(&written).status.success());
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&written).unwrap()).unwrap();
    assert_eq!(doc["methods"][0]["method"], "scripted baseline");
    assert!(
        doc["urdf"]
            .as_str()
            .unwrap()
            .contains("<robot name=\"fairino_fr3\">")
    );
    assert!(!dir.join("replay.html").exists(), "no --out: no HTML");
    // Written over: it is a replay JSON now.
    assert!(run(&written).status.success());
    std::fs::remove_dir_all(&dir).ok();
}
