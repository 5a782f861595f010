//! The contact family `heavy_slippery` against the scripts: knowing the cube's pose exactly does
//! not help (the oracle fails on ≥ 30 % of scenarios, and its failures are cubes left on the
//! table, not collisions), while a harder squeeze, which the scripts never give, does.

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, Outcome, Policy, run_episode};
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{EnvConfig, GraspEnv};
use fairgrasp_planner::ClosedLoopGrasp;

const EPISODES: usize = 100;

fn rate(config: &EnvConfig, policy: &mut dyn Policy) -> EvalReport {
    let mut env = GraspEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(config, 0, EPISODES).unwrap();
    let results = scenarios
        .iter()
        .map(|s| run_episode(&mut env, policy, s, None).unwrap())
        .collect();
    EvalReport::from_results(results)
}

#[test]
fn the_oracle_script_fails_on_at_least_30_percent_of_heavy_slippery_cubes() {
    let config = presets::load("heavy_slippery").unwrap();
    let oracle = rate(&config, &mut ClosedLoopGrasp::oracle(&config));
    eprintln!(
        "heavy_slippery: oracle {:.3} {:?}",
        oracle.success_rate, oracle.outcomes
    );
    assert!(oracle.success_rate <= 0.7, "oracle {:?}", oracle.outcomes);
    // It closes on the cube and lifts; the cube stays: no collision, no protective stop.
    let crashed = oracle.count(Outcome::Collision) + oracle.count(Outcome::ProtectiveStop);
    assert_eq!(crashed, 0, "oracle {:?}", oracle.outcomes);
}

#[test]
fn the_oracle_with_a_12_newton_squeeze_lifts_at_least_90_percent_of_them() {
    let mut config = presets::load("heavy_slippery").unwrap();
    config.gripper.force = 12.0;
    let oracle = rate(&config, &mut ClosedLoopGrasp::oracle(&config));
    eprintln!(
        "heavy_slippery, 12 N: oracle {:.3} {:?}",
        oracle.success_rate, oracle.outcomes
    );
    assert!(oracle.success_rate >= 0.9, "oracle {:?}", oracle.outcomes);
}
