//! Every config and checkpoint file is read only if it is a regular file within its size cap:
//! a FIFO given as a config is refused at once (it used to hang), `/dev/zero` behind a `.toml`
//! name is refused (it used to grow to gigabytes), and so is an oversized TOML (a 50 MB one
//! used to abort after allocating 3 GB). Each refusal names the file.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;
use common::command;

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
    let mut child = command()
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

/// A FIFO nobody writes (`fifo.EXT`) and a link to `/dev/zero` (`zero.EXT`) in `dir`: files
/// that block or never end if read.
fn special_files(dir: &std::path::Path, ext: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let fifo = dir.join(format!("fifo.{ext}"));
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let zero = dir.join(format!("zero.{ext}"));
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    (fifo, zero)
}

#[test]
fn fifos_devices_and_huge_files_are_refused_naming_the_file() {
    let dir = scratch("files");
    let (fifo, zero) = special_files(&dir, "toml");
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
    let out = command()
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

/// A URDF path is read only as a regular file within the URDF cap, by the rule configs follow
/// (`fairgrasp_types::fs::read_bounded`): a FIFO nobody writes used to block `joints --urdf`
/// forever, and `/dev/zero` behind a `.urdf` name was read up to the cap.
#[test]
fn urdf_paths_are_read_only_as_regular_files() {
    let dir = scratch("urdf-files");
    let (fifo, zero) = special_files(&dir, "urdf");
    for path in [&fifo, &zero] {
        let p = path.to_str().unwrap();
        refused(&["joints", "--urdf", p], &[p, "not a regular file"]);
        refused(
            &["fk", "--urdf", p, "--joints", "0"],
            &[p, "not a regular file"],
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Errors quote bounded excerpts of their input: a 1 MB TOML line of short words (which the
/// long-word cut in `main.rs` does not shorten) used to be echoed whole; an unconnected URDF of
/// 20 000 links listed every root link; a TOML file with old-Mac CR line endings was quoted
/// whole as its "line 1".
#[test]
fn messages_quote_bounded_excerpts_of_the_input() {
    let dir = scratch("quotes");
    let long_line = dir.join("long_line.toml");
    let ones = vec!["1"; 300_000].join(", ");
    std::fs::write(&long_line, format!("[scene]\ncube_mass = [{ones}]\n")).unwrap();
    let cr = dir.join("old_mac.toml");
    let mut text = String::from("[physics]\r");
    for i in 0..2000 {
        text.push_str(&format!("# comment {i}\r"));
    }
    text.push_str("[scene]\rcube_mass = 0.1\r");
    std::fs::write(&cr, text).unwrap();
    let unconnected = dir.join("unconnected.urdf");
    let links: String = (0..20_000)
        .map(|i| format!("  <link name=\"l{i}\"/>\n"))
        .collect();
    std::fs::write(
        &unconnected,
        format!("<robot name=\"r\">\n{links}</robot>\n"),
    )
    .unwrap();
    for (args, needles) in [
        (
            vec!["baseline", "--preset", long_line.to_str().unwrap()],
            &["line 2", "characters)"][..],
        ),
        (
            vec!["baseline", "--preset", cr.to_str().unwrap()],
            &["line 1", "CR"][..],
        ),
        (
            vec!["joints", "--urdf", unconnected.to_str().unwrap()],
            &["20000 root links", "l0, l1, l2", "and 19995 more"][..],
        ),
    ] {
        let out = fairgrasp(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        let head = &stderr[..stderr.len().min(600)];
        assert_eq!(out.status.code(), Some(1), "{args:?}: {head}");
        assert!(
            stderr.len() < 1_000,
            "{args:?}: {} bytes: {head}",
            stderr.len()
        );
        for n in needles {
            assert!(stderr.contains(n), "{args:?}: `{n}` not in {head}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// An error cites the line it is on whether the file ends its lines with LF, CRLF or CR (old
/// Mac): a URDF with CR line endings used to report every error on line 1.
#[test]
fn errors_cite_the_right_line_for_lf_crlf_and_cr_files() {
    let dir = scratch("line-ends");
    let urdf = [
        "<?xml version=\"1.0\"?>",
        "<robot name=\"r\">",
        "  <link name=\"a\"/>",
        "  <link name=\"b\"/>",
        "  <joint name=\"j\" type=\"fixed\">",
        "    <origin xyz=\"0 0 abc\"/>",
        "    <parent link=\"a\"/>",
        "    <child link=\"b\"/>",
        "  </joint>",
        "</robot>",
    ];
    let toml = [
        "[physics]",
        "dt = 0.01",
        "",
        "[scene]",
        "cube_mass = \"heavy\"",
    ];
    for (name, end) in [("lf", "\n"), ("crlf", "\r\n"), ("cr", "\r")] {
        let path = dir.join(format!("{name}.urdf"));
        std::fs::write(&path, urdf.join(end) + end).unwrap();
        refused(
            &["joints", "--urdf", path.to_str().unwrap()],
            &["line 6", "abc"],
        );
        if name != "cr" {
            // TOML allows LF and CRLF only; a CR file is refused on its line 1 (above).
            let path = dir.join(format!("{name}.toml"));
            std::fs::write(&path, toml.join(end) + end).unwrap();
            refused(
                &["baseline", "--preset", path.to_str().unwrap()],
                &["line 5", "heavy"],
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
