//! What leaves the simulator is what was evaluated: episodes exported as servo streams (a
//! script and a learned policy, several presets) are within the FR3's limits and ≤ 1° per
//! sample, and when played back in the env — the arm tracking the samples at the stream's
//! period — every exported successful grasp succeeds again.

use fairgrasp_env::cell::Cell;
use fairgrasp_env::episode::Outcome;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_evaluate::compare::methods::Method;
use fairgrasp_evaluate::export::export_episode;
use fairgrasp_planner::stream::check::peaks;
use fairgrasp_planner::stream::{StreamLimits, check_stream, play};

/// Exports `method` on the first `n` scenarios of `preset` (set `seed`) at `period` and plays
/// each successful one back; returns (exported successes, played successes, largest tracking
/// error \[deg\], largest step \[deg\]).
fn export_and_play(
    preset: &str,
    method: &str,
    n: usize,
    seed: u64,
    period: f64,
) -> (usize, usize, f64, f64) {
    let config: EnvConfig = fairgrasp_env::config::presets::load(preset).unwrap();
    let limits = StreamLimits::of(&Cell::from_config(&config).model);
    let scenarios = scenario_set(&config, seed, n).unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let (mut exported, mut replayed, mut lag, mut step) = (0, 0, 0.0f64, 0.0f64);
    for (k, scenario) in scenarios.iter().enumerate() {
        let resolved = Method::resolve(method, config.task.kind).unwrap();
        let e = export_episode(&config, scenario, resolved, period, 25, &limits).unwrap();
        let stream = &e.resampled.stream;
        check_stream(&stream.joints, period, &limits).expect("export checks its streams");
        step = step.max(peaks(&stream.joints, period).step_deg);
        assert_eq!(
            stream.joints[0], scenario.start_joints,
            "{preset} #{k} starts at its start"
        );
        if e.outcome != Outcome::Success {
            continue;
        }
        exported += 1;
        let report = play(&mut env, scenario, stream).unwrap();
        lag = lag.max(report.max_tracking_error.to_degrees());
        if report.outcome == Outcome::Success {
            replayed += 1;
        } else {
            eprintln!(
                "{preset} #{k} by {method}: exported a success, played {}",
                report.outcome
            );
        }
    }
    println!(
        "{method} on {preset}: {exported}/{n} exported successes, {replayed} played back as \
         successes; largest step {step:.3}°/sample, servo lag ≤ {lag:.3}°"
    );
    (exported, replayed, lag, step)
}

#[test]
fn exported_successful_grasps_of_a_script_still_succeed_when_played_back() {
    let (exported, replayed, lag, step) = export_and_play("sector", "open_loop", 24, 11, 0.008);
    assert!(
        exported >= 20,
        "only {exported} of 24 episodes succeeded before export"
    );
    assert_eq!(replayed, exported);
    assert!(step <= 1.0 && lag < 0.5, "step {step}°, lag {lag}°");
    // A coarser and a finer period, on the harder preset with the oracle.
    let (exported, replayed, _, _) = export_and_play("full", "oracle", 12, 12, 0.016);
    assert!(
        exported >= 10 && replayed == exported,
        "{replayed}/{exported} at 16 ms"
    );
    let (exported, replayed, _, _) = export_and_play("full", "oracle", 6, 13, 0.002);
    assert!(
        exported >= 5 && replayed == exported,
        "{replayed}/{exported} at 2 ms"
    );
}

#[test]
fn exported_successful_grasps_of_learned_policies_still_succeed_when_played_back() {
    let (exported, replayed, _, step) = export_and_play("nudged", "residual_nudged", 20, 14, 0.008);
    assert!(
        exported >= 16,
        "only {exported} of 20 episodes succeeded before export"
    );
    assert_eq!(replayed, exported);
    assert!(step <= 1.0);
    // A pure policy's TCP commands turn the joints within a step and reverse them at full
    // acceleration: the stream (jerk-limited, slowed where a reversal needs more than a step)
    // differs most from the simulated arm, and a few marginal grasps are lost (93 of 97 played
    // back as successes on scenario set 7, docs/real_cell.md).
    let (exported, replayed, _, step) = export_and_play("full", "pure_full", 20, 15, 0.008);
    assert!(
        exported >= 16,
        "only {exported} of 20 episodes succeeded before export"
    );
    assert!(replayed + 2 >= exported, "{replayed} of {exported}");
    assert!(step <= 1.0);
}
