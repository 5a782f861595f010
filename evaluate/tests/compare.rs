//! The comparison experiment called as a library: identical scenarios for every method, the
//! recorded episode reproduces its evaluation, bad requests are refused before anything runs.

use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use fairgrasp_env::config::presets;
use fairgrasp_evaluate::compare::{
    CompareError, CompareEvent, CompareOutput, ComparePreset, CompareSpec, LearnedPolicy,
    RecordedTrajectory, run_comparison, scripts_for,
};
use fairgrasp_policy::shipped::ShippedPolicy;
use fairgrasp_types::{ArmSimulation, Comparison, MethodResult, RecordedEpisode};

fn preset(name: &str) -> ComparePreset {
    ComparePreset {
        name: name.into(),
        config: presets::load(name).unwrap(),
    }
}

fn spec(names: &[&str], episodes: usize) -> CompareSpec {
    CompareSpec {
        presets: names.iter().map(|n| preset(n)).collect(),
        episodes,
        seed: 11,
        threads: 2,
        episode: None,
        replay_episodes: 2,
        command: "fairgrasp compare (test)".into(),
    }
}

fn shipped_residual() -> Vec<LearnedPolicy> {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("rl-compare-shipped");
    let dir = ShippedPolicy::ResidualHard
        .checkpoint_dir_in(&root)
        .unwrap();
    LearnedPolicy::load_all(&[dir]).unwrap()
}

/// The learned policy's method name in the comparison of [`shipped_residual`].
const AGENT: &str = "residual PPO: residual_hard";

/// The report names of the scripts a comparison on the lift presets runs (the lift task's
/// controls in the planner's table).
fn lift_scripts() -> Vec<&'static str> {
    let sector = presets::load("sector").unwrap();
    scripts_for([&sector]).iter().map(|c| c.report).collect()
}

/// Every method's name in the comparison: the scripts, then the learned policy.
fn methods() -> Vec<&'static str> {
    let mut methods = lift_scripts();
    methods.push(AGENT);
    methods
}

/// The comparison on `fixed` and `sector`, 3 episodes each, with the episodes it reported done
/// and the `preset/method` of each method it said it started, in order.
fn compare_fixed_and_sector() -> (CompareOutput, usize, Vec<String>) {
    let learned = shipped_residual();
    let (episodes_done, started) = (AtomicUsize::new(0), Mutex::new(Vec::new()));
    let out = run_comparison(&spec(&["fixed", "sector"], 3), &learned, &|e| match e {
        CompareEvent::Episode { .. } => {
            episodes_done.fetch_add(1, Ordering::Relaxed);
        }
        CompareEvent::Method { preset, method } => {
            started.lock().unwrap().push(format!("{preset}/{method}"));
        }
        CompareEvent::MethodDone { .. } | CompareEvent::Recording { .. } => {}
    })
    .unwrap();
    (
        out,
        episodes_done.into_inner(),
        started.into_inner().unwrap(),
    )
}

/// The first of the 3 scenarios of `preset` where the baseline and the learned policy end
/// differently, else 0: the scenario the comparison records.
fn first_differing_scenario(c: &Comparison, preset: &str) -> usize {
    let [base, agent] =
        [0, lift_scripts().len()].map(|i| &c.get(&c.methods[i], preset).unwrap().report.results);
    (0..3)
        .find(|&i| base[i].outcome != agent[i].outcome)
        .unwrap_or(0)
}

/// The trajectory `rec` names among the comparison's episodes.
fn trajectory_of<'a>(out: &'a CompareOutput, rec: &RecordedEpisode) -> &'a RecordedTrajectory {
    out.episodes
        .iter()
        .find(|t| rec.trajectory == format!("episodes/{}.json.gz", t.stem))
        .unwrap_or_else(|| panic!("no trajectory for {}", rec.trajectory))
}

/// Every method of every preset met the same scenarios (seeds and cube positions), the scripts
/// without a policy, the learned one with its run folder.
fn assert_the_same_scenarios_for_every_method(c: &Comparison) {
    for p in &c.presets {
        let scripts = lift_scripts();
        for script in &scripts {
            assert!(c.get(script, p).unwrap().policy.is_none(), "{script}");
        }
        let [a, b] = [0, scripts.len()].map(|i| c.get(&c.methods[i], p).unwrap());
        let seeds = |r: &MethodResult| {
            r.report
                .results
                .iter()
                .map(|e| (e.seed, e.object_xy))
                .collect::<Vec<_>>()
        };
        assert_eq!(seeds(a), seeds(b), "{p}: methods met different scenarios");
        assert_eq!(a.arm, ArmSimulation::Servo);
        assert_eq!(
            (a.seed, a.policy.is_none(), b.policy.is_some()),
            (11, true, true)
        );
    }
    assert!(
        c.run_folders[0].ends_with("residual_hard"),
        "{:?}",
        c.run_folders
    );
}

/// One recording per method, of `sector`'s first scenario where the baseline and the learned
/// policy differ, each with its evaluation's outcome and step count.
fn assert_the_recorded_episodes_reproduce_their_evaluation(out: &CompareOutput) {
    let c = &out.comparison;
    let k = first_differing_scenario(c, "sector");
    assert_eq!(c.recorded.len(), methods().len());
    for (i, rec) in c.recorded.iter().enumerate() {
        let traj = trajectory_of(out, rec);
        let evaluated = &c.get(&c.methods[i], "sector").unwrap().report.results[k];
        assert_eq!((rec.preset.as_str(), rec.episode), ("sector", k));
        assert_eq!(rec.outcome, evaluated.outcome, "{}", rec.method);
        assert_eq!(
            traj.trajectory.rows.len(),
            evaluated.steps + 1,
            "{}",
            rec.method
        );
        assert_eq!(traj.trajectory.outcome, Some(evaluated.outcome));
    }
}

/// The replay: every method on scenarios 0 and 1 of every preset (and that preset's first
/// scenario where the baseline and the learned policy differ), each replaying its evaluation.
fn assert_the_replay_reproduces_every_evaluation(out: &CompareOutput) {
    let c = &out.comparison;
    let mut replayed = 0;
    for p in &c.presets {
        let picked = if first_differing_scenario(c, p) < 2 {
            2
        } else {
            3
        };
        let here = c.replay.iter().filter(|r| &r.preset == p).count();
        assert_eq!(here, methods().len() * picked, "{p}");
        replayed += here;
    }
    assert_eq!(c.replay.len(), replayed);
    assert_eq!(out.episodes.len(), c.replay.len());
    for rec in &c.replay {
        let evaluated = &c.get(&rec.method, &rec.preset).unwrap().report.results[rec.episode];
        let traj = &trajectory_of(out, rec).trajectory;
        assert_eq!(rec.outcome, evaluated.outcome, "{}", rec.trajectory);
        assert_eq!(traj.rows.len(), evaluated.steps + 1, "{}", rec.trajectory);
        assert_eq!(traj.scene.bodies.len(), traj.rows[0].bodies.len());
    }
    assert!(c.recorded.iter().all(|r| c.replay.contains(r)));
}

/// Saved, every recorded episode is a file, and (for a spreadsheet) also a CSV; the replay's
/// other episodes are saved compact only.
fn assert_the_saved_episodes_are_there(out: &CompareOutput) {
    let c = &out.comparison;
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("rl-compare-episodes");
    std::fs::remove_dir_all(&dir).ok();
    out.save_episodes(&dir).unwrap();
    for rec in &c.recorded {
        assert!(dir.join(&rec.trajectory).is_file(), "{}", rec.trajectory);
        let csv = rec.trajectory.replace(".json.gz", ".csv");
        assert!(dir.join(&csv).is_file(), "{csv}");
    }
    let csvs = std::fs::read_dir(dir.join("episodes"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "csv")
        })
        .count();
    assert_eq!(csvs, c.recorded.len());
}

#[test]
fn every_method_meets_the_same_scenarios_and_the_recorded_episode_reproduces_its_evaluation() {
    let (out, episodes_done, started) = compare_fixed_and_sector();
    let c = &out.comparison;
    let methods = methods();
    assert_eq!(c.methods, methods);
    assert_eq!(c.presets, vec!["fixed", "sector"]);
    assert_eq!(episodes_done, 2 * methods.len() * 3);
    let expected: Vec<String> = ["fixed", "sector"]
        .iter()
        .flat_map(|p| methods.iter().map(move |m| format!("{p}/{m}")))
        .collect();
    assert_eq!(started, expected);
    assert_eq!(c.results.len(), 2 * methods.len());
    assert_the_same_scenarios_for_every_method(c);
    assert_the_recorded_episodes_reproduce_their_evaluation(&out);
    assert_the_replay_reproduces_every_evaluation(&out);
    assert_the_saved_episodes_are_there(&out);
}

#[test]
fn bad_requests_are_refused_before_any_episode_runs() {
    let never = |_: CompareEvent<'_>| panic!("nothing may run for a refused request");
    let e = run_comparison(&spec(&["fixed", "sector", "fixed"], 2), &[], &never).unwrap_err();
    assert!(matches!(e, CompareError::Request(_)));
    assert_eq!(e.to_string(), "--preset fixed is given twice");
    let mut out_of_range = spec(&["fixed"], 2);
    out_of_range.episode = Some(2);
    let e = run_comparison(&out_of_range, &[], &never).unwrap_err();
    assert!(
        e.to_string()
            .contains("--episode 2: the scenario sets have 2 episodes (0–1)"),
        "{e}"
    );
    let e = run_comparison(&spec(&[], 2), &[], &never).unwrap_err();
    assert!(e.to_string().contains("no preset"), "{e}");
}

/// The contact family in a comparison: the shipped squeezing residual squeezes there too (a
/// comparison hands each policy's grip force to the env, as training did) and lifts far more
/// of the heavy, slippery cubes than the oracle script, which knows their pose exactly.
#[test]
fn the_squeezing_residual_beats_the_oracle_script_on_heavy_slippery_cubes_in_a_comparison() {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("rl-compare-squeeze");
    let dir = ShippedPolicy::ResidualHeavySlippery
        .checkpoint_dir_in(&root)
        .unwrap();
    let learned = LearnedPolicy::load_all(&[dir]).unwrap();
    let mut s = spec(&["heavy_slippery"], 40);
    s.replay_episodes = 0;
    let out = run_comparison(&s, &learned, &|_| {}).unwrap();
    let c = &out.comparison;
    let rate = |method: &str| c.get(method, "heavy_slippery").unwrap().report.success_rate;
    let learned_name = c.methods.last().unwrap().clone();
    let (residual, oracle) = (rate(&learned_name), rate("oracle script"));
    eprintln!("{learned_name}: {residual:.3}, oracle script {oracle:.3}");
    assert!(residual >= 0.85, "{residual}");
    assert!(residual >= oracle + 0.4, "{residual} vs {oracle}");
}

/// The workers share one queue of episodes across methods and presets: the results do not
/// depend on how many there are, and equal each method evaluated alone, scenario by scenario.
#[test]
fn the_shared_episode_queue_gives_each_method_its_own_evaluation_whatever_the_threads() {
    let learned = shipped_residual();
    let run = |threads: usize| {
        let mut s = spec(&["sector", "nudged"], 7);
        s.threads = threads;
        s.replay_episodes = 0;
        let events = Mutex::new(Vec::new());
        let out = run_comparison(&s, &learned, &|e| {
            if let CompareEvent::MethodDone { preset, method, .. } = e {
                events.lock().unwrap().push(format!("{preset}/{method}"));
            }
        })
        .unwrap();
        (out.comparison, events.into_inner().unwrap())
    };
    let (one, done_one) = run(1);
    let (three, done_three) = run(3);
    assert_eq!(one.results, three.results);
    assert_eq!(done_one.len(), one.results.len());
    let mut sorted = done_three.clone();
    sorted.sort();
    let mut expected = done_one.clone();
    expected.sort();
    assert_eq!(
        sorted, expected,
        "every method finishes once on every preset"
    );
    let config = presets::load("nudged").unwrap();
    let scenarios = fairgrasp_env::scenario::scenario_set(&config, 11, 7).unwrap();
    let make = || fairgrasp_planner::ClosedLoopGrasp::observed(&config);
    let alone =
        fairgrasp_env::episode::evaluate(&config, &scenarios, 1, None, &make, &|| {}).unwrap();
    let compared = three.get("closed-loop script", "nudged").unwrap();
    assert_eq!(compared.report.results, alone.results);
}

/// The generalist in a comparison: one policy that grasps on every family it was trained for
/// (each specialist fails outside its own: docs/contact.md), using the push, the wrist view and
/// the squeeze as each comes.
#[test]
fn the_generalist_grasps_on_every_family_it_was_trained_for() {
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("rl-compare-generalist");
    let dir = ShippedPolicy::ResidualGeneralist
        .checkpoint_dir_in(&root)
        .unwrap();
    let learned = LearnedPolicy::load_all(&[dir]).unwrap();
    let families = ["nudged", "wrist_camera", "heavy_slippery", "full"];
    let mut s = spec(&families, 30);
    s.replay_episodes = 0;
    let out = run_comparison(&s, &learned, &|_| {}).unwrap();
    let c = &out.comparison;
    let learned_name = c.methods.last().unwrap().clone();
    for family in families {
        let rate = |method: &str| c.get(method, family).unwrap().report.success_rate;
        let (generalist, script) = (rate(&learned_name), rate("scripted baseline"));
        eprintln!("{family}: {learned_name} {generalist:.3}, open-loop script {script:.3}");
        assert!(generalist >= 0.85, "{family}: {generalist}");
        assert!(generalist >= script, "{family}: {generalist} vs {script}");
    }
    let heavy = |method: &str| c.get(method, "heavy_slippery").unwrap().report.success_rate;
    assert!(heavy(&learned_name) >= heavy("oracle script") + 0.4);
}

#[test]
fn a_place_comparison_runs_the_place_scripts_and_refuses_a_lift_preset_beside_them() {
    let out = run_comparison(&spec(&["place", "place_fixture_error"], 4), &[], &|_| {}).unwrap();
    let c = &out.comparison;
    // The place task's four scripts (the cell's three more need its mix), in the table's order.
    assert_eq!(
        c.methods,
        [
            "place script",
            "place script + force search",
            "closed-loop place",
            "closed-loop place + force search",
        ]
    );
    // Seated on the noise-free preset; the replay records the place task's episodes.
    let seated = &c.get("place script", "place").unwrap().report;
    assert_eq!(seated.successes, 4, "{:?}", seated.outcomes);
    assert!(c.replay.iter().any(|r| r.preset == "place_fixture_error"));
    let mixed = run_comparison(&spec(&["place", "sector"], 2), &[], &|_| {});
    let message = mixed
        .expect_err("a place and a lift preset together")
        .to_string();
    assert!(
        message.contains("place") && message.contains("sector"),
        "{message}"
    );
}
