//! The env benchmark as a library call: it steps what it was asked and its rates agree with its
//! times; nonsense is refused before any stepping.

use fairgrasp_bench::env::{EnvBenchError, EnvBenchSpec, bench_env};
use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets;

fn small_spec(config: EnvConfig) -> EnvBenchSpec {
    EnvBenchSpec {
        config,
        threads: 1,
        envs_per_thread: 2,
        steps: 15,
        resets: 4,
    }
}

#[test]
fn bench_env_steps_what_it_was_asked_and_its_rates_agree_with_its_times() {
    let mut config = presets::load("sector").unwrap();
    config.physics.substeps = 10;
    let called = std::cell::Cell::new(0);
    let r = bench_env(&small_spec(config), &|| called.set(called.get() + 1)).unwrap();
    assert_eq!(called.get(), 1);
    assert_eq!((r.threads, r.envs, r.env_steps), (1, 2, 30.0));
    assert_eq!(r.substeps, 10, "the config's substeps, not the default 20");
    // Physics steps are counted only for env steps that simulated (free-space ones run none).
    assert!((0.0..=1.0).contains(&r.simulated_share));
    assert!((r.physics_steps_per_s / r.env_steps_per_s - 10.0 * r.simulated_share).abs() < 1e-9);
    assert!((r.env_steps_per_s * r.wall_s - r.env_steps).abs() < 1e-6 * r.env_steps);
    assert!(
        r.cpu_s > 0.0 && (r.env_steps_per_cpu_s * r.cpu_s - r.env_steps).abs() < 1e-6 * r.env_steps
    );
    // Reset times are reported, fastest no slower than the mean (which is slower, hard or soft,
    // is a benchmark's question, not a test's: this machine is shared and noisy).
    assert!(
        r.soft_reset_min_ms > 0.0 && r.hard_reset_min_ms > 0.0,
        "{r:?}"
    );
    assert!(r.soft_reset_min_ms <= r.soft_reset_ms && r.hard_reset_min_ms <= r.hard_reset_ms);
    assert!(r.episodes_ended <= 30);
}

#[test]
fn bench_env_refuses_zero_steps_with_a_message() {
    let mut spec = small_spec(presets::load("fixed").unwrap());
    spec.steps = 0;
    let e = bench_env(&spec, &|| panic!("must not start stepping")).unwrap_err();
    assert!(matches!(e, EnvBenchError::Empty { steps: 0, .. }));
    assert!(e.to_string().contains("steps (0)"), "{e}");
}
