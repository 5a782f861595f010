//! Every config and checkpoint file is read only if it is a regular file within its size cap:
//! a FIFO given as a config is refused at once (it used to hang), `/dev/zero` behind a `.toml`
//! name is refused (it used to grow to gigabytes), and so is an oversized TOML (a 50 MB one
//! used to abort after allocating 3 GB). Each refusal names the file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bounded-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs fairgrasp with `args`; a command still running after 60 s is killed and fails the test
/// (the refusals here come at once; a FIFO used to block forever).
fn fairgrasp(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().ok();
            panic!("{args:?} still ran after 60 s: it blocked on its input");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn refused(args: &[&str], needles: &[&str]) {
    let out = fairgrasp(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: `{n}` not in {stderr}");
    }
}

#[test]
fn fifos_devices_and_huge_files_are_refused_naming_the_file() {
    let dir = scratch("files");
    let fifo = dir.join("fifo.toml");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success()
    );
    let zero = dir.join("zero.toml");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let huge = dir.join("huge.toml");
    let mut text = String::from("[task]\n");
    while text.len() <= 2 << 20 {
        text.push_str("# padding padding padding padding padding padding padding padding\n");
    }
    std::fs::write(&huge, text).unwrap();

    for path in [&fifo, &zero] {
        let p = path.to_str().unwrap();
        refused(
            &["baseline", "--preset", p, "--episodes", "1"],
            &[p, "not a regular file"],
        );
        refused(&["train", "--config", p], &[p, "not a regular file"]);
    }
    let p = huge.to_str().unwrap();
    refused(
        &["baseline", "--preset", p, "--episodes", "1"],
        &[p, "more than the 1048576"],
    );

    // A checkpoint whose meta.json is a FIFO.
    let checkpoint = dir.join("checkpoint");
    std::fs::create_dir_all(&checkpoint).unwrap();
    assert!(
        Command::new("mkfifo")
            .arg(checkpoint.join("meta.json"))
            .status()
            .unwrap()
            .success()
    );
    refused(
        &[
            "eval",
            "--policy",
            checkpoint.to_str().unwrap(),
            "--episodes",
            "1",
        ],
        &["meta.json", "not a regular file"],
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_empty_tmpdir_never_puts_files_in_the_working_directory() {
    // `eval` unpacks the shipped policy into the temporary folder; with TMPDIR="" it used to
    // unpack into the folder it ran in.
    let dir = scratch("tmpdir");
    let out = Command::new(env!("CARGO_BIN_EXE_fairgrasp"))
        .args([
            "eval",
            "--preset",
            "fixed",
            "--episodes",
            "1",
            "--threads",
            "1",
        ])
        .env("TMPDIR", "")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert!(
        left.is_empty(),
        "files written into the working directory: {left:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A bad value of 100 000 characters is quoted as a short excerpt and its length, wherever it
/// comes from: a flag (clap's message), a preset name, a TOML line the parser quotes.
#[test]
fn a_huge_bad_value_is_quoted_as_an_excerpt() {
    let dir = scratch("excerpt");
    let digits = "9".repeat(100_000);
    let name = "y".repeat(100_000);
    let toml = dir.join("huge.toml");
    std::fs::write(&toml, format!("[scene]\ncube_mass = {digits}\n")).unwrap();
    let toml = toml.to_str().unwrap();
    for (args, code) in [
        (vec!["baseline", "--episodes", &digits], 2),
        (vec!["fk", "--joints", "0", "0", "0", "0", "0", &digits], 2),
        (vec!["compare", "--preset", &name], 1),
        (vec!["baseline", "--preset", toml], 1),
    ] {
        let out = fairgrasp(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(code),
            "{}",
            &stderr[..stderr.len().min(400)]
        );
        assert!(
            stderr.len() < 2_000 && stderr.contains("characters)"),
            "{} bytes: {}",
            stderr.len(),
            &stderr[..stderr.len().min(400)]
        );
    }
}
