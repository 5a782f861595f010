//! A resumed run is the run it was (issue 60): whatever folder `train --resume` is started from,
//! it continues on the presets and teachers the run started with, or it is refused naming what
//! differs, and the refusal changes nothing in the run folder. What the recipe names is kept in
//! `RUN/inputs.toml` (`fairgrasp_rl::run::inputs`); the preset file itself is trained on from the
//! run's copy (`tests/run_folders.rs`).

use std::path::{Path, PathBuf};

mod common;
use common::{ok, stderr, train_in};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-resume-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A recipe of tiny updates (2 envs × 16 steps, evaluated after each on 2 episodes) with
/// `lines` (the preset, a mix, a kickstart table) at its top.
fn recipe(path: &Path, lines: &str, tail: &str) {
    std::fs::write(
        path,
        format!(
            "{lines}\ntotal_timesteps = 64\nn_envs = 2\nthreads = 1\neval_every = 1\neval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n{tail}"
        ),
    )
    .unwrap();
}

/// Every file of the run folder (but its lock) with its bytes, to show a refusal wrote nothing.
fn files(run: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![run.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.file_name().is_some_and(|n| n != ".lock") {
                out.push((path.clone(), std::fs::read(&path).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// The evaluation success rate of each row of `metrics.csv`.
fn eval_rates(run: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(run.join("metrics.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header
        .iter()
        .position(|c| *c == "eval_success_rate")
        .unwrap();
    lines
        .map(|l| l.split(',').nth(column).unwrap().to_string())
        .collect()
}

/// The fixed preset with a 40-step episode limit: no grasp on it succeeds (the scripted lift
/// takes 52 steps), so an evaluation on it scores 0 where the fixed preset scores 1.
const SHORT_FIXED: &str =
    "[randomization]\nposition = false\nyaw = false\n[task]\nmax_steps = 40\n";

/// Two working folders whose `env.toml` differ: `a`'s is the fixed preset, `b`'s [`SHORT_FIXED`].
fn two_folders(dir: &Path) -> (PathBuf, PathBuf) {
    let (a, b) = (dir.join("a"), dir.join("b"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let fixed = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/configs/fixed.toml");
    std::fs::copy(fixed, a.join("env.toml")).unwrap();
    std::fs::write(b.join("env.toml"), SHORT_FIXED).unwrap();
    (a, b)
}

#[test]
fn a_mix_preset_file_that_reads_differently_from_another_folder_is_refused_by_name() {
    let dir = temp_dir("mix");
    let (a, b) = two_folders(&dir);
    let config = dir.join("mix.toml");
    recipe(&config, "preset = \"fixed\"\nmix = [\"env.toml\"]", "");
    let run = dir.join("run");
    ok(&train_in(&a, &config, &run, &[]));
    let before = files(&run);
    // From `b`, the recipe's `env.toml` is another env: before this, the run went on with it
    // without a word (its evaluations fell from 100 % to 50 %).
    let refused = train_in(&b, &config, &run, &["--resume", "--timesteps", "128"]);
    assert_eq!(refused.status.code(), Some(1), "{}", stderr(&refused));
    let e = stderr(&refused);
    for needle in [
        "mix preset `env.toml`",
        "task.max_steps: 200 → 40",
        "--accept-config-changes",
    ] {
        assert!(e.contains(needle), "`{needle}` not in {e}");
    }
    assert_eq!(
        files(&run),
        before,
        "a refused resume changed the run folder"
    );
    // From the folder it started in, it goes on, on the same envs: every evaluation scores as
    // the first two did.
    ok(&train_in(
        &a,
        &config,
        &run,
        &["--resume", "--timesteps", "128"],
    ));
    let rates = eval_rates(&run);
    assert_eq!(rates.len(), 4);
    assert!(rates.iter().all(|r| r == &rates[0]), "{rates:?}");
    // Accepted, the new env is trained on and the change is recorded.
    ok(&train_in(
        &b,
        &config,
        &run,
        &["--resume", "--timesteps", "192", "--accept-config-changes"],
    ));
    let log = std::fs::read_to_string(run.join("config_changes.log")).unwrap();
    assert!(
        log.contains("mix preset `env.toml`") && log.contains("task.max_steps"),
        "{log}"
    );
    let record = std::fs::read_to_string(run.join("inputs.toml")).unwrap();
    assert!(record.contains("max_steps = 40"), "{record}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_preset_that_reads_differently_than_when_the_run_started_is_refused_by_name() {
    let dir = temp_dir("named");
    let config = dir.join("fixed.toml");
    recipe(&config, "preset = \"fixed\"", "");
    let run = dir.join("run");
    ok(&train_in(&dir, &config, &run, &[]));
    // As another build of fairgrasp whose `fixed` preset had another episode limit would.
    let path = run.join("inputs.toml");
    let record = std::fs::read_to_string(&path).unwrap();
    let edited = record.replacen("max_steps = 200\n", "max_steps = 40\n", 1);
    assert_ne!(
        edited, record,
        "the record has no max_steps = 200: {record}"
    );
    std::fs::write(&path, &edited).unwrap();
    let refused = train_in(&dir, &config, &run, &["--resume", "--timesteps", "128"]);
    let e = stderr(&refused);
    assert_eq!(refused.status.code(), Some(1), "{e}");
    assert!(
        e.contains("preset `fixed` reads differently") && e.contains("task.max_steps: 40 → 200"),
        "{e}"
    );
    // A record that is not one is refused naming the file, not taken as no record.
    std::fs::write(&path, "presets = 3\n").unwrap();
    let refused = train_in(&dir, &config, &run, &["--resume", "--timesteps", "128"]);
    let e = stderr(&refused);
    assert!(
        !refused.status.success() && e.contains("inputs.toml"),
        "{e}"
    );
    // A run with no record (an older fairgrasp's) gets one, and says so.
    std::fs::remove_file(&path).unwrap();
    let resumed = train_in(&dir, &config, &run, &["--resume", "--timesteps", "128"]);
    ok(&resumed);
    assert!(
        stderr(&resumed).contains("keeps no record"),
        "{}",
        stderr(&resumed)
    );
    assert_eq!(std::fs::read_to_string(&path).unwrap(), record);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_resume_that_accepts_another_preset_file_trains_on_that_file_and_keeps_its_copy() {
    let dir = temp_dir("switch");
    let (a, _) = two_folders(&dir);
    std::fs::write(a.join("short.toml"), SHORT_FIXED).unwrap();
    let (first, second) = (dir.join("first.toml"), dir.join("second.toml"));
    recipe(&first, "preset = \"env.toml\"", "");
    recipe(&second, "preset = \"short.toml\"", "");
    let run = dir.join("run");
    ok(&train_in(&a, &first, &run, &[]));
    assert_eq!(eval_rates(&run), ["1.0000", "1.0000"]);
    let refused = train_in(&a, &second, &run, &["--resume", "--timesteps", "128"]);
    assert!(
        stderr(&refused).contains("preset: \"env.toml\" → \"short.toml\""),
        "{}",
        stderr(&refused)
    );
    ok(&train_in(
        &a,
        &second,
        &run,
        &["--resume", "--timesteps", "128", "--accept-config-changes"],
    ));
    // Before, the resume kept training on the old file's copy while config.toml named the new.
    assert_eq!(
        std::fs::read_to_string(run.join("env.toml")).unwrap(),
        SHORT_FIXED
    );
    assert_eq!(eval_rates(&run)[2..], ["0.0000", "0.0000"]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_teacher_named_by_a_relative_folder_is_the_same_teacher_from_any_folder() {
    let dir = temp_dir("teacher");
    let (a, b) = two_folders(&dir);
    let plain = dir.join("plain.toml");
    recipe(&plain, "preset = \"fixed\"", "");
    // Two teachers of the same agent, trained with different seeds, one in each folder.
    ok(&train_in(
        &a,
        &plain,
        Path::new("teacher"),
        &["--seed", "1"],
    ));
    ok(&train_in(
        &b,
        &plain,
        Path::new("teacher"),
        &["--seed", "2"],
    ));
    let student = dir.join("student.toml");
    recipe(
        &student,
        "preset = \"fixed\"",
        "[kickstart]\nteachers = [\"teacher\"]\nweight = 1.0\n",
    );
    let run = dir.join("run");
    ok(&train_in(&a, &student, &run, &[]));
    let before = files(&run);
    let refused = train_in(&b, &student, &run, &["--resume", "--timesteps", "128"]);
    let e = stderr(&refused);
    assert_eq!(refused.status.code(), Some(1), "{e}");
    let named = |d: &Path| {
        std::fs::canonicalize(d.join("teacher/checkpoints/best"))
            .unwrap()
            .display()
            .to_string()
    };
    assert!(
        e.contains("kickstart.teachers[0] `teacher`")
            && e.contains(&named(&b))
            && e.contains(&named(&a)),
        "{e}"
    );
    assert_eq!(
        files(&run),
        before,
        "a refused resume changed the run folder"
    );
    ok(&train_in(
        &a,
        &student,
        &run,
        &["--resume", "--timesteps", "128"],
    ));
    std::fs::remove_dir_all(&dir).ok();
}
