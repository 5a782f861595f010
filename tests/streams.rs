//! Streams as Unix tools treat them: output into a pipe nobody reads ends the command quietly;
//! output onto a full device is a one-line error with exit code 1. Neither is a panic.

use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

fn fairgrasp() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
}

#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    // The read end is closed before the command prints anything: its baseline runs first.
    let mut child = fairgrasp()
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
    let out = fairgrasp()
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
