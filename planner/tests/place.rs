//! The place task's open-loop script on its noise-free preset: it grasps, carries, seats the
//! cube in the 2 mm-clearance pocket, releases it and moves clear on every scenario it can
//! see exactly (docs/place.md: 300 / 300 on set 7 with `fairgrasp baseline --preset place`).

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{Outcome, evaluate_seeded};
use fairgrasp_planner::ScriptedPlace;

#[test]
fn the_place_script_seats_the_cube_on_the_noise_free_preset() {
    let config = presets::load("place").unwrap();
    let report = evaluate_seeded(
        &config,
        3,
        40,
        2,
        None,
        &|| ScriptedPlace::new(&config),
        &|| {},
    )
    .unwrap();
    assert!(
        report.successes >= 39,
        "{} of 40 seated: {:?}",
        report.successes,
        report.outcomes
    );
    // The lift script on the same scenarios lifts the cube but never places it.
    let lift = evaluate_seeded(
        &config,
        3,
        5,
        1,
        None,
        &|| fairgrasp_planner::ScriptedGrasp::new(&config, Default::default()),
        &|| {},
    )
    .unwrap();
    assert_eq!(lift.successes, 0, "{:?}", lift.outcomes);
    assert!(lift.results.iter().all(|r| r.outcome != Outcome::Success));
}
