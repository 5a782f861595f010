//! What the root package's tests share: the `fairgrasp` binary, run as a user runs it.
//! Each test file that needs it says `mod common;` and takes the functions it uses, so a
//! function one file does not call is not dead code there.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
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

/// Writes a training recipe on `preset` that trains in seconds (`total_timesteps` env steps, 2
/// envs on 1 thread, updates of 16 steps, an evaluation of 2 episodes every 2 updates) to
/// `DIR/tiny.toml`, and returns its path and the run folder `DIR/run` to train it into.
pub fn tiny_recipe(dir: &Path, preset: &str, total_timesteps: u32) -> (PathBuf, PathBuf) {
    let config = dir.join("tiny.toml");
    std::fs::write(
        &config,
        format!(
            "preset = \"{preset}\"\ntotal_timesteps = {total_timesteps}\nn_envs = 2\nthreads = 1\n\
             eval_every = 2\neval_episodes = 2\n[ppo]\nn_steps = 16\nbatch_size = 16\nn_epochs = 1\n"
        ),
    )
    .unwrap();
    (config, dir.join("run"))
}

/// Runs `fairgrasp train --config CONFIG --run-dir RUN` and waits for it.
pub fn train(config: &Path, run: &Path) -> Output {
    fairgrasp(&[
        "train",
        "--config",
        config.to_str().unwrap(),
        "--run-dir",
        run.to_str().unwrap(),
    ])
}

/// Runs `fairgrasp train --config CONFIG --run-dir RUN FLAGS…` in the folder `cwd` (without the
/// kill tests' crash hook) and waits for it.
pub fn train_in(cwd: &Path, config: &Path, run: &Path, flags: &[&str]) -> Output {
    command()
        .current_dir(cwd)
        .arg("train")
        .arg("--config")
        .arg(config)
        .arg("--run-dir")
        .arg(run)
        .args(flags)
        .env_remove("FAIRGRASP_CRASH_AT")
        .output()
        .unwrap()
}

/// Asserts that a command succeeded, showing its stderr if not.
pub fn ok(o: &Output) {
    assert!(o.status.success(), "{}", stderr(o));
}

/// What a run printed to stderr, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// What a run printed to stdout, as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A pytest suite with Python packages of its own: its venv (under the repository root), the
/// requirements file the venv is made from, and the folder pytest runs.
pub struct PythonSuite {
    pub venv: &'static str,
    pub requirements: &'static str,
    pub tests: &'static str,
}

/// `scripts/python-package-test.sh` as a command, run in the repository root: pytest in a venv
/// the script makes on first use, with the extension this build made (`lib_native.so`, beside
/// the test binary in `target/<profile>/deps/`; without it the script builds one with maturin)
/// and this build's `fairgrasp` binary (`FAIRGRASP_BIN`). `suite`: `None` runs the package's own
/// suite (`python/tests` in `target/python-package-venv`).
pub fn pytest(suite: Option<&PythonSuite>) -> Command {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let native = std::env::current_exe()
        .ok()
        .and_then(|exe| exe.parent().map(|deps| deps.join("lib_native.so")));
    let mut command = Command::new("bash");
    command
        .arg(root.join("scripts/python-package-test.sh"))
        .env("FAIRGRASP_BIN", env!("CARGO_BIN_EXE_fairgrasp"))
        .current_dir(root);
    if let Some(lib) = native.filter(|p| p.exists()) {
        command.env("FAIRGRASP_NATIVE_LIB", lib);
    }
    if let Some(suite) = suite {
        command
            .env("FAIRGRASP_PY_VENV", root.join(suite.venv))
            .env("FAIRGRASP_PY_REQUIREMENTS", root.join(suite.requirements))
            .env("FAIRGRASP_PY_TESTS", suite.tests);
    }
    command
}
