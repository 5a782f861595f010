//! Training never sees an evaluation scenario: training episodes draw their scenarios from seeds
//! with the top bit set, evaluation sets from seeds without it.

use fairgrasp_env::config::presets;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::vec::VecEnv;
use fairgrasp_rl::run::train::TRAINING_SEEDS;

#[test]
fn training_and_evaluation_scenario_seeds_are_disjoint() {
    let config = presets::load("sector").unwrap();
    for set_seed in [0, 1, 5, 1_000_000, 1_000_000_000] {
        let set = scenario_set(&config, set_seed, 300).unwrap();
        assert!(
            set.iter().all(|s| s.seed & TRAINING_SEEDS == 0),
            "set {set_seed}"
        );
    }
    // A vectorised env started the way training starts it hands out top-bit seeds only.
    let mut vec = VecEnv::new(&config, 4, 1, TRAINING_SEEDS | 7_919).unwrap();
    vec.reset().unwrap();
    assert!(vec.batch().seeds.iter().all(|s| s & TRAINING_SEEDS != 0));
}
