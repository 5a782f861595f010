//! Run folders never lose history: a folder whose `checkpoints/latest` is missing or damaged is
//! refused by `train` and `train --resume` with what is missing and what to do, and `--force`
//! moves it aside instead of deleting it; a folder that is not a run's is never written into; a
//! line of `metrics.csv` that cannot be read is set aside, not dropped with every row around it;
//! one process trains in a folder at a time (a lock that a killed run does not leave behind);
//! and a resume trains on the run's own copy of its preset file, wherever it is started.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::{command, ok, stderr, train_in};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-folders-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A run of `updates` tiny updates (2 envs × 16 steps) on `preset`, evaluated after each one.
fn write_config(dir: &Path, name: &str, preset: &str, updates: u64) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(
        &path,
        format!(
            "preset = \"{preset}\"\ntotal_timesteps = {}\nn_envs = 2\nthreads = 1\neval_every = 1\neval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n",
            32 * updates
        ),
    )
    .unwrap();
    path
}

fn train(config: &Path, run: &Path, flags: &[&str]) -> Output {
    train_in(Path::new(env!("CARGO_MANIFEST_DIR")), config, run, flags)
}

/// The update numbers of `metrics.csv`'s rows.
fn metric_updates(run: &Path) -> Vec<u64> {
    std::fs::read_to_string(run.join("metrics.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect()
}

#[test]
fn a_run_without_its_latest_checkpoint_is_refused_and_force_moves_it_aside() {
    let dir = temp_dir("damaged");
    let config = write_config(&dir, "tiny.toml", "fixed", 4);
    let run = dir.join("run");
    ok(&train(&config, &run, &[]));
    std::fs::remove_dir_all(run.join("checkpoints/latest")).unwrap();
    let metrics = std::fs::read(run.join("metrics.csv")).unwrap();
    let best = std::fs::read(run.join("checkpoints/best/meta.json")).unwrap();
    for flags in [&[][..], &["--resume"][..]] {
        let refused = train(&config, &run, flags);
        assert!(!refused.status.success(), "{flags:?} was accepted");
        let message = stderr(&refused);
        assert!(
            message.contains("4 rows of metrics.csv")
                && message.contains("checkpoints/best")
                && message.contains("--force"),
            "{flags:?}: {message}"
        );
        assert_eq!(std::fs::read(run.join("metrics.csv")).unwrap(), metrics);
        assert_eq!(
            std::fs::read(run.join("checkpoints/best/meta.json")).unwrap(),
            best
        );
    }
    // `latest` replaced by a file: refused too.
    std::fs::write(run.join("checkpoints/latest"), "not a checkpoint").unwrap();
    let refused = train(&config, &run, &["--resume"]);
    assert!(
        stderr(&refused).contains("cannot be read"),
        "{}",
        stderr(&refused)
    );
    // --force keeps the old run, whole, beside the new one.
    let forced = train(&config, &run, &["--force"]);
    ok(&forced);
    let aside = dir.join("run.replaced-1");
    assert!(
        stderr(&forced).contains("run.replaced-1"),
        "{}",
        stderr(&forced)
    );
    assert_eq!(std::fs::read(aside.join("metrics.csv")).unwrap(), metrics);
    assert_eq!(
        std::fs::read(aside.join("checkpoints/best/meta.json")).unwrap(),
        best
    );
    assert_eq!(metric_updates(&run), vec![1, 2, 3, 4]);
    // A healthy run is also moved aside by --force (to the next free name), never deleted.
    ok(&train(&config, &run, &["--force"]));
    assert!(
        dir.join("run.replaced-2/checkpoints/latest/meta.json")
            .is_file()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_folder_that_is_not_a_run_is_never_written_into() {
    let dir = temp_dir("foreign");
    let config = write_config(&dir, "tiny.toml", "fixed", 1);
    let folder = dir.join("paper");
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("config.toml"), "title = \"my thesis\"\n").unwrap();
    std::fs::write(folder.join("metrics.csv"), "week,pages\n1,3\n").unwrap();
    for flags in [&[][..], &["--force"][..], &["--resume"][..]] {
        let refused = train(&config, &folder, flags);
        assert!(!refused.status.success(), "{flags:?} was accepted");
        assert!(
            stderr(&refused).contains("not a run folder"),
            "{}",
            stderr(&refused)
        );
        let mut names: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, ["config.toml", "metrics.csv"], "{flags:?}");
        assert_eq!(
            std::fs::read_to_string(folder.join("config.toml")).unwrap(),
            "title = \"my thesis\"\n"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unreadable_metrics_line_is_set_aside_and_every_other_row_kept() {
    let dir = temp_dir("utf8");
    let run = dir.join("run");
    ok(&train(
        &write_config(&dir, "four.toml", "fixed", 4),
        &run,
        &[],
    ));
    let text = std::fs::read(run.join("metrics.csv")).unwrap();
    // One byte of row 2 becomes invalid UTF-8.
    let row2 = text.windows(3).position(|w| w == b"\n2,").unwrap() + 3;
    let mut damaged = text.clone();
    damaged.insert(row2, 0xFF);
    std::fs::write(run.join("metrics.csv"), &damaged).unwrap();
    let resumed = train(
        &write_config(&dir, "six.toml", "fixed", 6),
        &run,
        &["--resume"],
    );
    ok(&resumed);
    assert!(
        stderr(&resumed).contains("1 torn, unreadable or extra lines set aside"),
        "{}",
        stderr(&resumed)
    );
    assert_eq!(metric_updates(&run), vec![1, 3, 4, 5, 6]);
    let rejected = std::fs::read(run.join("metrics.rejected.csv")).unwrap();
    assert!(rejected.starts_with(b"2,\xFF"), "{rejected:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A child process that is killed when the test lets go of it (a failed assertion included).
struct KillOnDrop(std::process::Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn one_process_per_run_folder_and_a_killed_one_leaves_no_lock_behind() {
    let dir = temp_dir("lock");
    let config = write_config(&dir, "long.toml", "fixed", 1_000_000);
    let run = dir.join("run");
    // At most two minutes, and killed when the test ends, whether it passes or not.
    let mut first = KillOnDrop(
        command()
            .args(["train", "--max-wall-time", "120", "--config"])
            .arg(&config)
            .arg("--run-dir")
            .arg(&run)
            .env_remove("FAIRGRASP_CRASH_AT")
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    let started = Instant::now();
    while !run.join("checkpoints/latest/meta.json").is_file() {
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no checkpoint"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let pid = first.0.id().to_string();
    for flags in [&["--resume"][..], &["--force"][..]] {
        let refused = train(&config, &run, flags);
        assert!(!refused.status.success(), "{flags:?} was accepted");
        assert!(
            stderr(&refused).contains("in use") && stderr(&refused).contains(&pid),
            "{}",
            stderr(&refused)
        );
    }
    assert!(!dir.join("run.replaced-1").exists());
    first.0.kill().unwrap();
    first.0.wait().unwrap();
    // The lock file still names the killed process; its lock died with it.
    let resumed = train(&config, &run, &["--resume", "--max-wall-time", "1"]);
    ok(&resumed);
    assert!(
        stderr(&resumed).contains(&format!("lock file of process {pid}")),
        "{}",
        stderr(&resumed)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_resume_trains_on_the_runs_copy_of_its_preset_file_from_any_folder() {
    let dir = temp_dir("snapshot");
    let (started_in, resumed_in) = (dir.join("a"), dir.join("b"));
    std::fs::create_dir_all(&started_in).unwrap();
    std::fs::create_dir_all(&resumed_in).unwrap();
    let fixed = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/configs/fixed.toml");
    std::fs::copy(fixed, started_in.join("cell.toml")).unwrap();
    let run = dir.join("run");
    let bin = env!("CARGO_BIN_EXE_fairgrasp");
    let four = write_config(&dir, "four.toml", "cell.toml", 4);
    let six = write_config(&dir, "six.toml", "cell.toml", 6);
    let in_folder = |cwd: &Path, config: &Path, flags: &[&str]| {
        Command::new(bin)
            .current_dir(cwd)
            .arg("train")
            .arg("--config")
            .arg(config)
            .arg("--run-dir")
            .arg(&run)
            .args(flags)
            .env_remove("FAIRGRASP_CRASH_AT")
            .output()
            .unwrap()
    };
    ok(&in_folder(&started_in, &four, &[]));
    assert_eq!(
        std::fs::read(run.join("env.toml")).unwrap(),
        std::fs::read(fixed).unwrap()
    );
    // Another folder's cell.toml is not a valid env at all: the resume must not read it.
    std::fs::write(resumed_in.join("cell.toml"), "[scene\n").unwrap();
    let resumed = in_folder(&resumed_in, &six, &["--resume"]);
    ok(&resumed);
    assert!(
        stderr(&resumed).contains("own copy"),
        "{}",
        stderr(&resumed)
    );
    assert_eq!(metric_updates(&run), vec![1, 2, 3, 4, 5, 6]);
    std::fs::remove_dir_all(&dir).ok();
}
