//! A short soak (the long one is `fairgrasp bench soak`, figures in the README): random actions
//! on two presets never give a non-finite observation or reward, or an env error.

use fairgrasp_bench::soak::{ZeroActions, soak};
use fairgrasp_env::config::presets;

#[test]
fn random_actions_never_give_a_non_finite_value_or_an_env_error() {
    for name in ["hard", "nudged"] {
        let config = presets::load(name).unwrap();
        let r = soak(&config, &mut ZeroActions, 1.0, 3_000, 5, &mut |_| {}).unwrap();
        assert_eq!(r.steps, 3_000);
        assert!(r.episodes >= 10, "{name}: {r:?}");
        assert_eq!(
            (
                r.non_finite_observations,
                r.non_finite_rewards,
                r.env_errors
            ),
            (0, 0, 0),
            "{name}: {r:?}"
        );
        assert!(r.rss_end_kib > 0, "resident memory not read: {r:?}");
    }
}
