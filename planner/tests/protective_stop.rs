//! The protective stop against the scripted baseline: normal grasps on `full` never trip it, and
//! on `hard` (where a finger sometimes lands on the cube) no episode presses the cube more than
//! 2 mm into the table — the required test.

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{Outcome, Policy, evaluate_seeded};
use fairgrasp_env::scenario::{Scenario, scenario_set};
use fairgrasp_env::task::Failure;
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

/// The most the cube centre may go below its resting height \[m\].
const MAX_SINK: f64 = 0.002;

/// What one baseline episode did.
struct Episode {
    seed: u64,
    /// Deepest the cube centre went below its resting height, over every env step \[m\].
    sink: f64,
    success: bool,
    failure: Option<Failure>,
}

/// The cube centre's height in `world` \[m\].
fn object_world_z(env: &TaskEnv) -> f64 {
    (env.base_in_world().iso * env.object_in_base().iso)
        .translation
        .z
}

fn run(env: &mut TaskEnv, policy: &mut ScriptedGrasp, scenario: &Scenario) -> Episode {
    let (mut obs, _) = env.reset_to(scenario);
    policy.reset(scenario.seed);
    let rest_z = object_world_z(env);
    let mut sink = 0.0_f64;
    loop {
        let step = env.step(&policy.act(&obs)).unwrap();
        sink = sink.max(rest_z - object_world_z(env));
        obs = step.obs;
        if step.terminated || step.truncated {
            return Episode {
                seed: scenario.seed,
                sink,
                success: step.info.success,
                failure: step.info.failure,
            };
        }
    }
}

/// Every episode of the baseline on the `n` scenarios seed 0 draws (the CLI's default set),
/// on two threads.
fn baseline(config: &EnvConfig, n: usize) -> Vec<Episode> {
    let scenarios = scenario_set(config, 0, n).unwrap();
    std::thread::scope(|scope| {
        let handles: Vec<_> = scenarios
            .chunks(n.div_ceil(2))
            .map(|part| {
                scope.spawn(move || {
                    let mut env = TaskEnv::new(config.clone()).unwrap();
                    let mut policy = ScriptedGrasp::new(config, BaselineConfig::default());
                    part.iter()
                        .map(|s| run(&mut env, &mut policy, s))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    })
}

fn is_stop(e: &Episode) -> bool {
    matches!(e.failure, Some(Failure::ProtectiveStop { .. }))
}

#[test]
fn normal_grasps_on_full_never_trip_the_stop() {
    let config = presets::load("full").unwrap();
    let episodes = baseline(&config, 200);
    let failed: Vec<_> = episodes
        .iter()
        .filter(|e| !e.success)
        .map(|e| (e.seed, e.failure.clone()))
        .collect();
    assert!(failed.is_empty(), "full: failures {failed:?}");
    assert!(!episodes.iter().any(is_stop));
}

#[test]
fn no_hard_baseline_episode_presses_the_cube_2_mm_into_the_table() {
    let config = presets::load("hard").unwrap();
    let episodes = baseline(&config, 200);
    let pressed: Vec<_> = episodes
        .iter()
        .filter(|e| e.sink > MAX_SINK)
        .map(|e| (e.seed, e.sink))
        .collect();
    let stops = episodes.iter().filter(|e| is_stop(e)).count();
    let worst = episodes.iter().map(|e| e.sink).fold(0.0, f64::max);
    eprintln!(
        "hard: {stops} protective stops, worst sink {:.2} mm",
        worst * 1e3
    );
    assert!(pressed.is_empty(), "sank more than 2 mm: {pressed:?}");
    assert!(stops > 0, "hard has pressing episodes: the stop must trip");
    assert!(episodes.iter().all(|e| !(e.success && is_stop(e))));
}

#[test]
fn without_the_stop_the_hard_baseline_does_press_the_cube_into_the_table() {
    let mut config = presets::load("hard").unwrap();
    config.task.protective_stop_force = 1.0e9;
    let episodes = baseline(&config, 200);
    let pressed = episodes.iter().filter(|e| e.sink > MAX_SINK).count();
    let pressed_successes = episodes
        .iter()
        .filter(|e| e.sink > MAX_SINK && e.success)
        .count();
    eprintln!("hard without the stop: {pressed} pressed, {pressed_successes} of them successes");
    assert!(pressed > 0, "the required test above could not fail");
    assert!(!episodes.iter().any(is_stop));
}

#[test]
fn the_evaluation_names_a_stopped_episode_protective_stop() {
    let config = presets::load("hard").unwrap();
    let episodes = baseline(&config, 12);
    let make = || ScriptedGrasp::new(&config, BaselineConfig::default());
    let report = evaluate_seeded(&config, 0, 12, 2, None, &make, &|| {}).unwrap();
    let stopped: Vec<u64> = episodes
        .iter()
        .filter(|e| is_stop(e))
        .map(|e| e.seed)
        .collect();
    let named: Vec<u64> = report
        .results
        .iter()
        .filter(|r| r.outcome == Outcome::ProtectiveStop)
        .map(|r| r.seed)
        .collect();
    assert!(
        !stopped.is_empty(),
        "the first 12 hard scenarios include a press"
    );
    assert_eq!(stopped, named);
    assert_eq!(report.count(Outcome::ProtectiveStop), stopped.len());
}
