//! Outputs never clobber what fairgrasp did not write: `plot --out` refuses a run's own files,
//! a device, a foreign PNG, a path inside a report folder, and a path another of its outputs
//! takes; it replaces a chart it wrote. `baseline --record` records only into a new or empty
//! folder. Every refusal leaves the file as it was.

use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{command, stderr};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-outputs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn fairgrasp(args: &[&str], paths: &[&Path]) -> Output {
    command()
        .args(args)
        .args(paths)
        .env_remove("FAIRGRASP_CRASH_AT")
        .output()
        .unwrap()
}

/// A finished two-update run (2 envs × 16 steps on `fixed`).
fn tiny_run(dir: &Path) -> PathBuf {
    let config = dir.join("tiny.toml");
    std::fs::write(
        &config,
        "preset = \"fixed\"\ntotal_timesteps = 64\nn_envs = 2\nthreads = 1\neval_every = 1\neval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n",
    )
    .unwrap();
    let run = dir.join("run");
    let o = fairgrasp(
        &["train", "--config"],
        &[&config, Path::new("--run-dir"), &run],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    run
}

#[test]
fn plot_replaces_only_charts_it_wrote() {
    let dir = temp_dir("plot");
    let run = tiny_run(&dir);
    let plot = |out: &Path| fairgrasp(&["plot"], &[&run, Path::new("--out"), out]);
    let report = dir.join("report");
    std::fs::create_dir_all(&report).unwrap();
    std::fs::write(report.join(".fairgrasp-report"), "").unwrap();
    let photo = dir.join("photo.png");
    std::fs::write(&photo, b"\x89PNG\r\n\x1a\nsomebody's photo").unwrap();
    let cases: [(PathBuf, &str); 6] = [
        (run.join("metrics.csv"), "not a chart fairgrasp wrote"),
        (
            run.join("checkpoints/latest/model.bpk"),
            "not a chart fairgrasp wrote",
        ),
        (photo.clone(), "not a chart fairgrasp wrote"),
        (PathBuf::from("/dev/null"), "not a regular file"),
        (report.join("curves.png"), "inside the report folder"),
        (dir.join("curves.svg"), "ending in .png"),
    ];
    for (out, words) in &cases {
        let before = std::fs::read(out).ok();
        let refused = plot(out);
        assert!(!refused.status.success(), "{} was written", out.display());
        assert!(
            stderr(&refused).contains(words),
            "{}: {}",
            out.display(),
            stderr(&refused)
        );
        assert_eq!(std::fs::read(out).ok(), before, "{} changed", out.display());
    }
    let chart = dir.join("curves.png");
    for _ in 0..2 {
        let written = plot(&chart);
        assert!(written.status.success(), "{}", stderr(&written));
    }
    assert!(fairgrasp_types::output::png_is_ours(
        &std::fs::read(&chart).unwrap()
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn episodes_are_recorded_only_into_a_new_or_empty_folder() {
    let dir = temp_dir("record");
    let record = dir.join("episodes");
    std::fs::create_dir_all(&record).unwrap();
    std::fs::write(record.join("thesis.tex"), "\\chapter{Grasping}").unwrap();
    let args = [
        "baseline",
        "--preset",
        "fixed",
        "--episodes",
        "2",
        "--record",
    ];
    let refused = fairgrasp(&args, &[&record]);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("thesis.tex"),
        "{}",
        stderr(&refused)
    );
    std::fs::remove_file(record.join("thesis.tex")).unwrap();
    let recorded = fairgrasp(&args, &[&record]);
    assert!(recorded.status.success(), "{}", stderr(&recorded));
    assert!(record.join("episode_0001.json").is_file());
    // A second recording into the same folder would leave its episodes beside the first one's
    // with nothing to tell them apart (it used to, silently): refused, naming the folder and
    // what it holds, files untouched.
    let before = std::fs::read(record.join("episode_0001.json")).unwrap();
    let again = fairgrasp(
        &[
            "baseline",
            "--preset",
            "fixed",
            "--episodes",
            "1",
            "--seed",
            "3",
            "--record",
        ],
        &[&record],
    );
    let message = stderr(&again);
    assert_eq!(again.status.code(), Some(1), "{message}");
    assert!(
        message.contains(&record.display().to_string())
            && message.contains("holds 4 episode files")
            && message.contains("new or empty folder"),
        "{message}"
    );
    assert_eq!(
        std::fs::read(record.join("episode_0001.json")).unwrap(),
        before
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_dangling_out_link_is_named_as_one_with_its_target() {
    let dir = temp_dir("dangling");
    let link = dir.join("report");
    let target = dir.join("gone/report");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let recorded = dir.join("recorded");
    let o = fairgrasp(
        &[
            "baseline",
            "--preset",
            "fixed",
            "--episodes",
            "1",
            "--record",
        ],
        &[&recorded],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let episode = recorded.join("episode_0000.json");
    let said = format!(
        "{} is a dangling symbolic link: it points to {}, which does not exist",
        link.display(),
        target.display()
    );
    // The OS says "No such file or directory" (compare, record) or "File exists" (plot's
    // --out-dir): neither says that the path is a link, nor where it points.
    for (args, paths) in [
        (
            &["compare", "--preset", "fixed", "--episodes", "1", "--out"][..],
            vec![link.as_path()],
        ),
        (
            &["plot", "--out-dir"][..],
            vec![link.as_path(), episode.as_path()],
        ),
        (
            &[
                "baseline",
                "--preset",
                "fixed",
                "--episodes",
                "1",
                "--record",
            ][..],
            vec![link.as_path()],
        ),
    ] {
        let o = fairgrasp(args, &paths);
        let message = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {message}");
        assert!(message.contains(&said), "{args:?}: {message}");
        assert!(!target.exists(), "{args:?} created the link's target");
    }
    std::fs::remove_dir_all(&dir).ok();
}
