//! Episodes as Rerun recordings (`python/fairgrasp/rerun.py`, tested by `python/tests-rerun`,
//! pytest): `fairgrasp replay --json` (this build's binary) records two methods on one scenario,
//! `fairgrasp.rerun.save` writes the `.rrd`, and Rerun's own reader reads it back (entities and
//! time range). Run through `scripts/python-package-test.sh` in a venv of its own
//! (`target/python-rerun-venv`, created on the first run from `scripts/requirements-rerun.txt`:
//! rerun-sdk 0.41.0 beside the package's pins), with the extension `cargo test --workspace` has
//! just built. The Rust build itself has no Rerun dependency.

use std::process::Command;

#[test]
fn an_episode_written_as_rrd_reads_back_with_rerun() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    // target/<profile>/deps/rerun_file-HASH → target/<profile>/deps/lib_native.so, the
    // workspace build's cdylib (as tests/python_package.rs finds it).
    let exe = std::env::current_exe().unwrap();
    let native = exe.parent().map(|d| d.join("lib_native.so"));
    let mut cmd = Command::new("bash");
    cmd.arg(root.join("scripts/python-package-test.sh"));
    if let Some(lib) = native.filter(|p| p.exists()) {
        cmd.env("FAIRGRASP_NATIVE_LIB", lib);
    }
    let out = cmd
        .env("FAIRGRASP_BIN", env!("CARGO_BIN_EXE_fairgrasp"))
        .env("FAIRGRASP_PY_VENV", root.join("target/python-rerun-venv"))
        .env(
            "FAIRGRASP_PY_REQUIREMENTS",
            root.join("scripts/requirements-rerun.txt"),
        )
        .env("FAIRGRASP_PY_TESTS", "python/tests-rerun")
        .current_dir(root)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "pytest failed:\n{stdout}\n{stderr}");
    assert!(
        stdout.contains("4 passed") && !stdout.contains("skipped"),
        "every Rerun test must run here:\n{stdout}"
    );
}
