//! The scripted baseline on mounts that are not level on the table top: a tilted (wedge) mount
//! with the base yawed, and a raised pedestal. "Top-down" is along world gravity, whatever the
//! base's pose.

use fairgrasp_env::EnvConfig;
use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, evaluate_seeded};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

fn evaluate(config: &EnvConfig, seed: u64, n: usize) -> EvalReport {
    let make = || ScriptedGrasp::new(config, BaselineConfig::default());
    evaluate_seeded(config, seed, n, 2, None, &make, &|| {}).unwrap()
}

fn full_with_mount(xyz_offset: [f64; 3], rpy: [f64; 3]) -> EnvConfig {
    let mut config = presets::load("full").unwrap();
    for (v, d) in config.arm.base_xyz.iter_mut().zip(xyz_offset) {
        *v += d;
    }
    config.arm.base_rpy = rpy;
    config
}

#[test]
fn baseline_keeps_98_percent_with_the_base_tilted_10_degrees_and_yawed_90() {
    let config = full_with_mount([0.0; 3], [0.0, 10f64.to_radians(), 90f64.to_radians()]);
    let report = evaluate(&config, 7, 200);
    eprintln!("tilted: {:.3} {:?}", report.success_rate, report.outcomes);
    assert!(
        report.success_rate >= 0.98,
        "{:.3} {:?}",
        report.success_rate,
        report.outcomes
    );
}

#[test]
fn baseline_grasps_from_a_raised_rolled_pedestal_without_touching_the_table() {
    // 10 cm above the table top, rolled −8°, yawed −45°.
    let config = full_with_mount(
        [0.0, 0.0, 0.10],
        [-8f64.to_radians(), 0.0, -45f64.to_radians()],
    );
    let report = evaluate(&config, 8, 100);
    eprintln!("pedestal: {:.3} {:?}", report.success_rate, report.outcomes);
    assert!(report.success_rate >= 0.95, "{:?}", report.outcomes);
    assert!(report.collision_rate <= 0.02, "{:?}", report.outcomes);
}
