//! Streams as Unix tools treat them: output into a pipe nobody reads ends the command quietly;
//! output onto a full device is a one-line error with exit code 1. Neither is a panic.

use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

mod common;
use common::command;

#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    // The read end is closed before the command prints anything: its baseline runs first.
    let mut child = command()
        .args([
            "baseline",
            "--preset",
            "fixed",
            "--episodes",
            "8",
            "--threads",
            "1",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.is_empty(), "a closed pipe is not an error: {stderr}");
    // Killed by SIGPIPE, as `yes | head -1` kills `yes`.
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
}

#[test]
fn a_full_stdout_is_a_one_line_error() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = command()
        .args(["fk", "--joints", "0", "0", "0", "0", "0", "0", "--json"])
        .stdout(full)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stderr.starts_with("error: cannot write the output to stdout"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("streams-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs fairgrasp with `args` and its stdout a pipe whose read end is closed at once.
fn with_stdout_closed(args: &[&str]) -> std::process::Output {
    let mut child = command()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

#[test]
fn a_command_that_writes_files_finishes_them_when_nobody_reads_its_stdout() {
    let dir = scratch("closed");
    let recorded = dir.join("recorded");
    let out = with_stdout_closed(&[
        "baseline",
        "--preset",
        "fixed",
        "--episodes",
        "3",
        "--threads",
        "1",
        "--record",
        recorded.to_str().unwrap(),
    ]);
    assert!(recorded.join("episode_0002.json").is_file(), "{out:?}");
    // `plot` prints a line after each episode's chart and replay: a closed pipe used to end
    // it after the first, the other two episodes never drawn.
    let episodes: Vec<String> = (0..3)
        .map(|i| recorded.join(format!("episode_{i:04}.json")))
        .map(|p| p.to_str().unwrap().to_string())
        .collect();
    let mut args = vec!["plot"];
    args.extend(episodes.iter().map(String::as_str));
    let out = with_stdout_closed(&args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    for i in 0..3 {
        for ext in ["png", "gif"] {
            let file = recorded.join(format!("episode_{i:04}.{ext}"));
            assert!(file.is_file(), "{} missing; {stderr}", file.display());
        }
    }
    assert!(stderr.is_empty(), "a closed pipe is not an error: {stderr}");
    // Then it ends as any command ends on a closed pipe.
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
    // `compare` finishes its folder, and leaves no staging folder.
    let report = dir.join("report");
    let out = with_stdout_closed(&[
        "compare",
        "--preset",
        "fixed",
        "--episodes",
        "2",
        "--threads",
        "1",
        "--out",
        report.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("error"), "{stderr}");
    for file in [
        "report.md",
        "report.ipynb",
        "compare.csv",
        "compare.json",
        "replay.html",
    ] {
        assert!(report.join(file).is_file(), "{file} missing; {stderr}");
    }
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.contains(".partial")), "{names:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A tmpfs of 1 MiB mounted on a new folder, unmounted when dropped; None without the
/// permission to mount.
struct SmallDisk(std::path::PathBuf);

impl SmallDisk {
    fn mount() -> Option<SmallDisk> {
        let dir = scratch("small-disk");
        let mounted = Command::new("mount")
            .args(["-t", "tmpfs", "-o", "size=1m", "tmpfs"])
            .arg(&dir)
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        mounted.then_some(SmallDisk(dir))
    }
}

impl Drop for SmallDisk {
    fn drop(&mut self) {
        Command::new("umount").arg(&self.0).status().ok();
        std::fs::remove_dir_all(&self.0).ok();
    }
}

#[test]
fn a_full_disk_is_named_in_the_message() {
    let Some(disk) = SmallDisk::mount() else {
        eprintln!(
            "skipped: no permission to mount a tmpfs (the note's wording is tested in src/error_message.rs)"
        );
        return;
    };
    let out = command()
        .args([
            "compare",
            "--preset",
            "fixed",
            "--episodes",
            "2",
            "--threads",
            "1",
        ])
        .arg("--out")
        .arg(disk.0.join("report"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let error = stderr
        .lines()
        .find(|l| l.starts_with("error: "))
        .unwrap_or("");
    let mounted = format!("mounted on {}: 1.0 MiB in all", disk.0.display());
    assert!(error.contains("ran out of space"), "{stderr}");
    assert!(error.contains(&mounted), "{stderr}");
    assert_eq!(
        error.matches("No space left on device").count(),
        1,
        "the OS's reason once: {error}"
    );
    // Nothing of the unfinished report is left on the disk.
    assert_eq!(std::fs::read_dir(&disk.0).unwrap().count(), 0);
}
