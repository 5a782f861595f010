//! The place residual's interface ([`PlaceResidual`]): at a zero command it is the engineer's
//! force-guided search step for step, and a held correction moves where the search presses.

use fairgrasp_env::TaskEnv;
use fairgrasp_env::config::presets;
use fairgrasp_env::episode::Policy;
use fairgrasp_planner::place::residual::{FEATURE_DIM, PlaceResidual};
use fairgrasp_planner::place::script::PlacePhase;
use fairgrasp_planner::{ScriptedPlace, SearchParams, TaskResidual};

/// Each step's joint command and the episode's end, under `act`.
fn actions(
    preset: &str,
    seed: u64,
    mut act: impl FnMut(&fairgrasp_env::Observation) -> fairgrasp_env::Action,
) -> (Vec<[f64; 7]>, Option<fairgrasp_env::episode::Outcome>) {
    let config = presets::load(preset).unwrap();
    let mut env = TaskEnv::new(config).unwrap();
    let (mut obs, _) = env.reset(seed).unwrap();
    let mut out = Vec::new();
    loop {
        let a = act(&obs);
        out.push(a.0);
        let step = env.step(&a).unwrap();
        obs = step.obs;
        if step.terminated || step.truncated {
            return (out, step.info.episode.map(|r| r.outcome));
        }
    }
}

#[test]
fn a_zero_command_is_the_force_search_step_for_step() {
    let config = presets::load("place_grasp_error").unwrap();
    for seed in [1, 2] {
        let mut search = ScriptedPlace::with_search(&config, SearchParams::default());
        search.reset(seed);
        let want = actions("place_grasp_error", seed, |o| search.act(o));
        let mut residual = PlaceResidual::new(&config);
        residual.reset(seed);
        let got = actions("place_grasp_error", seed, |o| residual.act(o, &[0.0; 7]));
        assert_eq!(got, want, "seed {seed}");
    }
}

#[test]
fn a_held_command_shifts_the_search_and_the_features_report_it() {
    let config = presets::load("place").unwrap();
    let mut residual = PlaceResidual::new(&config);
    residual.reset(4);
    let mut features = [0.0; FEATURE_DIM];
    let (mut in_search, mut spiralled) = (0, false);
    let command = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    actions("place", 4, |o| {
        if residual.script().place_phase() == PlacePhase::Search {
            in_search += 1;
            residual.write_features(o, &mut features);
            spiralled |= features[3] == 1.0;
        }
        residual.act(o, &command)
    });
    assert!(in_search > 10, "the search ran {in_search} steps");
    // The correction followed the command toward +6 mm along the table's x, within its rate.
    let x = features[12];
    assert!(x > 0.5 && x <= 1.0, "correction_x {x}");
    assert_eq!(features[13], 0.0);
    // Several millimetres off a pocket with 2 mm of clearance, the cube lands on the rim and
    // the search spirals; uncorrected, on the noise-free preset, it goes straight in.
    assert!(spiralled, "the corrected search never spiralled");
    let mut plain = PlaceResidual::new(&config);
    plain.reset(4);
    let mut straight = true;
    actions("place", 4, |o| {
        plain.write_features(o, &mut features);
        straight &= features[3] == 0.0;
        plain.act(o, &[0.0; 7])
    });
    assert!(
        straight,
        "the uncorrected search spiralled on the noise-free preset"
    );
}
