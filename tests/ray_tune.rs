//! The Ray Tune sweep (`python/fairgrasp/tune.py`, tested by `python/tests-ray`, pytest) on a
//! local Ray with 2 CPUs: Rust trainings as Tune trials under ASHA; a trial whose training
//! diverges or is killed reported with its reason, a sweep whose driver is killed resumed with its
//! finished trial kept, bad arguments refused before Ray starts. Run through
//! `scripts/python-package-test.sh` in a venv of its own (`target/python-ray-venv`, created on
//! the first run from `scripts/requirements-ray.txt`: Ray Tune 2.60.0 beside the package's
//! pins), with the extension `cargo test --workspace` has just built and this build's
//! `fairgrasp` binary (the trials run `fairgrasp train`; `cargo test --workspace --features
//! fairgrasp/train` makes it a trainer). Without the `train` feature the binary cannot train,
//! so the test is not compiled.
#![cfg(feature = "train")]

mod common;

#[test]
fn a_ray_tune_sweep_of_rust_trainings_passes_its_pytest_suite() {
    let start = std::time::Instant::now();
    let out = common::pytest(Some(&common::PythonSuite {
        venv: "target/python-ray-venv",
        requirements: "scripts/requirements-ray.txt",
        tests: "python/tests-ray",
    }))
    .arg("-s")
    .output()
    .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "pytest failed:\n{stdout}\n{stderr}");
    assert!(
        stdout.contains("passed") && !stdout.contains("skipped"),
        "every Ray test must run here:\n{stdout}"
    );
    // The sweep's table, for the log (cargo test -- --nocapture shows it).
    println!(
        "{stdout}\n(venv and pytest: {:.0} s)",
        start.elapsed().as_secs_f64()
    );
}
