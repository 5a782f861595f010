//! `fairgrasp train` writes TensorBoard event files beside `metrics.csv`, read back here with
//! TensorBoard's own Python readers (`scripts/read-tensorboard.py` in the venv that
//! `scripts/python-env.sh` makes from `scripts/requirements-tensorboard.txt`): every cell of
//! every row is a scalar at the row's timestep with the cell's value, the config is there as
//! text, and a run killed after a row but before its event and then resumed has a second file,
//! no (tag, step) written twice, and the killed row's events.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-tb-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The interpreter of the TensorBoard venv (created on first use).
fn python_with_tensorboard() -> String {
    let venv = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tensorboard-venv");
    let out = Command::new("bash")
        .arg(repo().join("scripts/python-env.sh"))
        .arg(&venv)
        .arg(repo().join("scripts/requirements-tensorboard.txt"))
        .output()
        .expect("bash runs scripts/python-env.sh");
    assert!(
        out.status.success(),
        "scripts/python-env.sh failed (python3 with venv and PyPI access needed):\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap().trim().to_string()
}

fn train(config: &Path, run: &Path, resume: bool, crash_at: Option<&str>) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_fairgrasp"));
    cmd.args(["train", "--config"])
        .arg(config)
        .arg("--run-dir")
        .arg(run);
    if resume {
        cmd.arg("--resume");
    }
    match crash_at {
        Some(point) => cmd.env("FAIRGRASP_CRASH_AT", point),
        None => cmd.env_remove("FAIRGRASP_CRASH_AT"),
    };
    cmd.output().unwrap()
}

#[test]
fn tensorboard_reads_every_metrics_cell_once_also_across_a_kill_and_a_resume() {
    let dir = temp_dir("roundtrip");
    let config = dir.join("tiny.toml");
    // Four tiny updates (2 envs × 16 steps), an evaluation after every second one.
    std::fs::write(
        &config,
        "preset = \"fixed\"\ntotal_timesteps = 128\nn_envs = 2\nthreads = 1\neval_every = 2\n\
         eval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n",
    )
    .unwrap();
    let run = dir.join("run");
    // Killed after update 3's row reached metrics.csv, before its events were written.
    let killed = train(&config, &run, false, Some("after_row@3"));
    assert!(!killed.status.success(), "the crash point was not reached");
    let resumed = train(&config, &run, true, None);
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_progress_lines(&String::from_utf8_lossy(&resumed.stderr));
    let read = read_with_tensorboard(&run);
    assert_two_event_files_and_the_config(&read, &run);
    let (header, expected) = metrics_cells(&run);
    assert_every_cell_once_with_its_value(&read, &expected);
    for column in [
        "success_rate",
        "entropy",
        "approx_kl",
        "learning_rate",
        "stage",
        "steps_per_second",
        "eval_success_rate",
    ] {
        assert!(header.contains(&column.to_string()), "{column}");
    }
    assert_dashboard_shows_every_row(&read);
    std::fs::remove_dir_all(&dir).ok();
}

/// The live progress: lines on `stderr` with the stage, success, steps/s and time left, one of
/// them with the evaluation.
fn assert_progress_lines(stderr: &str) {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("train: "))
        .unwrap_or_else(|| panic!("no progress line:\n{stderr}"));
    for part in ["stage ", "success ", "steps/s", " left"] {
        assert!(line.contains(part), "{part} missing: {line}");
    }
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("train: ") && l.contains("eval ")),
        "no progress line with the evaluation:\n{stderr}"
    );
}

/// What `scripts/read-tensorboard.py` read from `run`'s event files (JSON: files, texts,
/// scalars, shown).
fn read_with_tensorboard(run: &Path) -> Value {
    let out = Command::new(python_with_tensorboard())
        .arg(repo().join("scripts/read-tensorboard.py"))
        .arg(run)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Two files (the killed invocation's and the resume's), each opening with its version; the
/// config as text, the TOML of `run`'s config.toml inside.
fn assert_two_event_files_and_the_config(read: &Value, run: &Path) {
    let files = read["files"].as_array().unwrap();
    assert_eq!(files.len(), 2, "{files:?}");
    for f in files {
        assert_eq!(f["file_version"], "brain.Event:2", "{f}");
        assert!(
            f["name"]
                .as_str()
                .unwrap()
                .starts_with("events.out.tfevents.")
        );
    }
    let saved = std::fs::read_to_string(run.join("config.toml")).unwrap();
    let texts = read["texts"].as_array().unwrap();
    assert!(!texts.is_empty());
    for t in texts {
        assert_eq!(t[0], "config/config.toml");
        assert!(t[2].as_str().unwrap().contains(saved.trim()), "{t}");
    }
}

/// `run`'s metrics.csv: its header, and every non-empty cell by (TensorBoard tag, the row's
/// timestep); the four rows' tags end in their column's name.
fn metrics_cells(run: &Path) -> (Vec<String>, HashMap<(String, i64), f64>) {
    let metrics = std::fs::read_to_string(run.join("metrics.csv")).unwrap();
    let mut lines = metrics.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut expected: HashMap<(String, i64), f64> = HashMap::new();
    let mut rows = 0;
    for line in lines {
        rows += 1;
        let cells: Vec<&str> = line.split(',').collect();
        let step: i64 = cells[header.iter().position(|c| *c == "timesteps").unwrap()]
            .parse()
            .unwrap();
        for (column, cell) in header.iter().zip(&cells) {
            if let Ok(v) = cell.parse::<f64>() {
                let tag = fairgrasp_rl::run::tensorboard::tag_of(column);
                assert!(tag.ends_with(&format!("/{column}")), "{tag}");
                expected.insert((tag, step), v);
            }
        }
    }
    assert_eq!(rows, 4);
    (header.iter().map(|h| h.to_string()).collect(), expected)
}

/// Every non-empty cell of metrics.csv (`expected`), once, at the row's timestep, with its value
/// (as f32, TensorBoard's precision).
fn assert_every_cell_once_with_its_value(read: &Value, expected: &HashMap<(String, i64), f64>) {
    let scalars = read["scalars"].as_array().unwrap();
    let mut seen = HashSet::new();
    for s in scalars {
        let key = (s[0].as_str().unwrap().to_string(), s[1].as_i64().unwrap());
        assert!(seen.insert(key.clone()), "{key:?} written twice");
        let want = expected
            .get(&key)
            .unwrap_or_else(|| panic!("{key:?} is not a cell of metrics.csv"));
        let got = s[2].as_f64().unwrap();
        assert_eq!(
            got as f32, *want as f32,
            "{key:?}: {got} vs metrics.csv {want}"
        );
    }
    assert_eq!(seen.len(), expected.len(), "cells of metrics.csv missing");
}

/// What TensorBoard's dashboard shows: every row's step for every always-present column, and
/// the two evaluations.
fn assert_dashboard_shows_every_row(read: &Value) {
    let shown = read["shown"].as_object().unwrap();
    let steps: Vec<i64> = shown["episodes/success_rate"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p[0].as_i64().unwrap())
        .collect();
    assert_eq!(steps, vec![32, 64, 96, 128]);
    assert_eq!(shown["eval/eval_success_rate"].as_array().unwrap().len(), 2);
}
