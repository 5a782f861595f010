//! Skipping physics in free space (`physics.free_space`) does not change what the scripted
//! baseline achieves: on the same scenarios, skipping on and off give success rates inside each
//! other's 95 % Wilson interval, and almost every episode ends the same way.
//! (All five presets at 200 episodes: `scripts/free_space_equivalence.sh`, figures in the README.)

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, evaluate_seeded};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

fn baseline(preset: &str, free_space: bool, episodes: usize) -> EvalReport {
    let mut config = presets::load(preset).unwrap();
    config.physics.free_space = free_space;
    let make = || ScriptedGrasp::new(&config, BaselineConfig::default());
    evaluate_seeded(&config, 0, episodes, 2, None, &make, &|| {}).unwrap()
}

fn equivalent(preset: &str, episodes: usize) {
    let (on, off) = (
        baseline(preset, true, episodes),
        baseline(preset, false, episodes),
    );
    eprintln!(
        "{preset}: on {:.3} {:?}, off {:.3} {:?}",
        on.success_rate, on.outcomes, off.success_rate, off.outcomes
    );
    // (1e-9: the interval's end is computed, 1.0 may come out as 0.999…)
    let inside = |x: &EvalReport, y: &EvalReport| {
        (y.ci_low - 1e-9..=y.ci_high + 1e-9).contains(&x.success_rate)
    };
    assert!(
        inside(&on, &off) && inside(&off, &on),
        "{preset}: on {:.3} [{:.3}, {:.3}], off {:.3} [{:.3}, {:.3}]",
        on.success_rate,
        on.ci_low,
        on.ci_high,
        off.success_rate,
        off.ci_low,
        off.ci_high
    );
    let same = on
        .results
        .iter()
        .zip(&off.results)
        .filter(|(a, b)| {
            assert_eq!(a.seed, b.seed);
            a.outcome == b.outcome
        })
        .count();
    assert!(
        same * 100 >= episodes * 95,
        "{preset}: only {same} of {episodes} episodes ended the same way"
    );
}

#[test]
fn skipping_free_space_keeps_the_baseline_on_full() {
    equivalent("full", 60);
}

#[test]
fn skipping_free_space_keeps_the_baseline_on_hard() {
    equivalent("hard", 100);
}
