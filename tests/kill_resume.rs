//! Kill tests: `train` aborted (as by a kill: no destructors, no flushing) at every point of an
//! update — while a checkpoint (`latest` or `best`) is written, once it is moved aside, before
//! and after the metrics row, and in the middle of the row — then `train --resume` (twice after
//! a kill that left only `latest.old`, since the next save must not delete the only copy): the run finishes with exactly one
//! `metrics.csv` row per update, in order, and `checkpoints/best` never scores lower than before
//! the kill. The abort comes from `FAIRGRASP_CRASH_AT` (see `fairgrasp_rl::run::resume::crash_point`).

use std::path::{Path, PathBuf};

mod common;
use common::command;

const UPDATES: u64 = 4;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-kill-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A run of four tiny updates (2 envs × 16 steps), evaluated after each one.
fn write_config(dir: &Path) -> PathBuf {
    let path = dir.join("tiny.toml");
    std::fs::write(
        &path,
        format!(
            "preset = \"fixed\"\ntotal_timesteps = {}\nn_envs = 2\nthreads = 1\neval_every = 1\neval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n",
            32 * UPDATES
        ),
    )
    .unwrap();
    path
}

fn train(config: &Path, run: &Path, resume: bool, crash_at: Option<&str>) -> std::process::Output {
    let mut cmd = command();
    cmd.arg("train")
        .arg("--config")
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

/// The update numbers of `metrics.csv`'s rows, and whether every line is complete.
fn metric_updates(run: &Path) -> (Vec<u64>, bool) {
    let text = std::fs::read_to_string(run.join("metrics.csv")).unwrap_or_default();
    let updates = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap_or(u64::MAX))
        .collect();
    (updates, text.ends_with('\n'))
}

fn best_score(run: &Path) -> f64 {
    let dir = run.join("checkpoints/best");
    let old = run.join("checkpoints/best.old/meta.json");
    let meta = std::fs::read_to_string(dir.join("meta.json"))
        .or_else(|_| std::fs::read_to_string(old))
        .ok();
    meta.map_or(-1.0, |m| {
        let v: serde_json::Value = serde_json::from_str(&m).unwrap();
        v["eval_success_rate"].as_f64().unwrap_or(-1.0)
    })
}

#[test]
fn a_kill_at_any_point_of_an_update_loses_no_row_duplicates_none_and_keeps_the_best() {
    let dir = temp_dir("points");
    let config = write_config(&dir);
    // `latest:`/`best:` name the checkpoint being written; the first evaluation always beats
    // "none yet", so `best` is written at update 1.
    let points = [
        "latest:checkpoint_written@0",
        "best:checkpoint_written@1",
        "best:checkpoint_moved_aside@1",
        "before_checkpoint@2",
        "latest:checkpoint_written@2",
        "latest:checkpoint_moved_aside@2",
        "before_row@2",
        "torn_row@2",
        "after_row@2",
        "before_row@4",
    ];
    let expected: Vec<u64> = (1..=UPDATES).collect();
    for point in points {
        let run = dir.join(point.replace('@', "_"));
        let killed = train(&config, &run, false, Some(point));
        assert!(
            !killed.status.success(),
            "{point}: the crash point was not reached"
        );
        let best_before = best_score(&run);
        if point.contains("moved_aside") {
            // Killed again at the same point of the resume's first save: that save must not
            // delete `.old`, the only copy left.
            let killed_again = train(&config, &run, true, Some(point));
            assert!(
                !killed_again.status.success(),
                "{point}: second crash not reached"
            );
            let kept = ["checkpoints/latest", "checkpoints/latest.old"]
                .iter()
                .any(|d| run.join(d).join("meta.json").exists());
            assert!(kept, "{point}: the second kill left no checkpoint");
        }
        let resumed = train(&config, &run, true, None);
        assert!(
            resumed.status.success(),
            "{point}: resume failed: {}",
            String::from_utf8_lossy(&resumed.stderr)
        );
        let (updates, complete) = metric_updates(&run);
        assert!(complete, "{point}: a torn last line remains");
        assert_eq!(updates, expected, "{point}: rows after the resume");
        let best_after = best_score(&run);
        assert!(
            best_after >= best_before,
            "{point}: best fell from {best_before} to {best_after}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_fresh_train_into_a_folder_killed_before_its_first_checkpoint_starts_over() {
    let dir = temp_dir("first");
    let config = write_config(&dir);
    let run = dir.join("run");
    let killed = train(&config, &run, false, Some("latest:checkpoint_written@0"));
    assert!(!killed.status.success());
    assert!(run.join("metrics.csv").exists() && !run.join("checkpoints/latest").exists());
    let again = train(&config, &run, false, None);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert_eq!(metric_updates(&run).0, (1..=UPDATES).collect::<Vec<_>>());
    // Now the folder holds a run: a fresh train is refused, naming --resume.
    let refused = train(&config, &run, false, None);
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--resume"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn resume_keeps_a_best_that_scored_higher_than_the_last_evaluation() {
    let dir = temp_dir("best");
    let config = write_config(&dir);
    let run = dir.join("run");
    assert!(train(&config, &run, false, None).status.success());
    // Pretend the best checkpoint scored 1.0 and `latest` records no evaluation (as a
    // checkpoint written before the best score was recorded in it): a resume that started
    // `best` from `latest`'s own score would let the first evaluation overwrite it.
    // Both as format version 1, which had no folder checksum to refuse the edit.
    let edit = |file: &str, f: &dyn Fn(&mut serde_json::Value)| {
        let path = run.join(file);
        let mut meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        f(&mut meta);
        meta["version"] = serde_json::json!(1);
        std::fs::write(&path, serde_json::to_vec_pretty(&meta).unwrap()).unwrap();
        std::fs::remove_file(path.with_file_name("checksum")).unwrap();
    };
    edit("checkpoints/best/meta.json", &|m| {
        m["eval_success_rate"] = serde_json::json!(1.0)
    });
    edit("checkpoints/latest/meta.json", &|m| {
        m["eval_success_rate"] = serde_json::Value::Null;
        m.as_object_mut().unwrap().remove("best_eval_success_rate");
    });
    let bigger = dir.join("longer.toml");
    let text = std::fs::read_to_string(&config).unwrap().replace(
        &format!("total_timesteps = {}", 32 * UPDATES),
        &format!("total_timesteps = {}", 64 * UPDATES),
    );
    std::fs::write(&bigger, text).unwrap();
    let resumed = train(&bigger, &run, true, None);
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_eq!(best_score(&run), 1.0, "best was overwritten by a worse one");
    assert_eq!(
        metric_updates(&run).0,
        (1..=2 * UPDATES).collect::<Vec<_>>()
    );
    std::fs::remove_dir_all(&dir).ok();
}
