//! What the root package's tests share: the `fairgrasp` binary, run as a user runs it.
//! Each test file that needs it says `mod common;` and takes the functions it uses, so a
//! function one file does not call is not dead code there.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// The `fairgrasp` binary as a command, run in the repository root (set another folder with
/// `.current_dir`).
pub fn command() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_fairgrasp"));
    command.current_dir(env!("CARGO_MANIFEST_DIR"));
    command
}

/// Runs `fairgrasp ARGS` in the repository root and waits for it.
pub fn fairgrasp(args: &[&str]) -> Output {
    fairgrasp_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

/// Runs `fairgrasp ARGS` in `dir` and waits for it.
pub fn fairgrasp_in(dir: &Path, args: &[&str]) -> Output {
    command()
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// What a run printed to stderr, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// What a run printed to stdout, as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
