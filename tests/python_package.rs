//! The Python package's tests (python/tests, pytest), run through
//! `scripts/python-package-test.sh` in its own venv (created on the first run), with the
//! extension `cargo test --workspace` has just built (`deps/lib_native.so`, beside this test's
//! binary; the script builds it with maturin if it is missing). Before, this test plays one
//! `full` episode in the Rust `TaskEnv` and hands its observations to pytest, which must see
//! the very same bits from Python.

mod common;

use fairgrasp_env::{Action, TaskEnv, config::presets};

/// One `full` episode from scenario 11 under smooth deterministic actions: the seed, the actions,
/// the observations (as the f64 values of their f32s, so JSON carries them exactly) and rewards.
fn rust_reference() -> serde_json::Value {
    let mut env = TaskEnv::new(presets::load("full").unwrap()).unwrap();
    let (first, _) = env.reset(11).unwrap();
    let as_f64 = |o: &fairgrasp_env::Observation| -> Vec<f64> {
        o.to_array().iter().map(|v| f64::from(*v)).collect()
    };
    let (mut observations, mut actions, mut rewards) = (vec![as_f64(&first)], vec![], vec![]);
    for t in 0..80 {
        let a: [f64; 7] = std::array::from_fn(|i| 0.8 * (0.1 * t as f64 + i as f64).sin());
        let step = env.step(&Action(a)).unwrap();
        observations.push(as_f64(&step.obs));
        actions.push(a.to_vec());
        rewards.push(step.reward);
        if step.terminated || step.truncated {
            break;
        }
    }
    serde_json::json!({"preset": "full", "seed": 11, "actions": actions,
                       "observations": observations, "rewards": rewards})
}

#[test]
fn the_python_package_passes_its_pytest_suite() {
    let reference =
        std::env::temp_dir().join(format!("fairgrasp-py-ref-{}.json", std::process::id()));
    std::fs::write(&reference, rust_reference().to_string()).unwrap();
    let out = common::pytest(None)
        .env("FAIRGRASP_RUST_REFERENCE", &reference)
        .output()
        .unwrap();
    std::fs::remove_file(&reference).ok();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "pytest failed:\n{stdout}\n{stderr}");
    assert!(
        stdout.contains("passed") && !stdout.contains("skipped"),
        "every Python test must run here:\n{stdout}"
    );
}
