//! The scenario's family in the mix, from a generator of its own (the rest of the scenario is
//! drawn as without the mix), and the errors it keeps.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::scenario::Scenario;
use crate::scenario::error_mix::settings::{ErrorFamily, ErrorMix};

/// The family of scenario `seed` in `mix`: one uniform draw against the cumulative weights.
pub fn draw_error_family(mix: &ErrorMix, seed: u64) -> ErrorFamily {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x6d69_785f_6661_6d31);
    let u: f64 = rng.random_range(0.0..1.0);
    let mut cumulative = 0.0;
    for (family, p) in ErrorFamily::ALL.into_iter().zip(mix.probabilities()) {
        cumulative += p;
        if u < cumulative {
            return family;
        }
    }
    // Rounding left u at or above the last sum: the last family with a weight.
    ErrorFamily::ALL
        .into_iter()
        .zip(mix.weights())
        .rev()
        .find(|(_, w)| *w > 0.0)
        .map_or(ErrorFamily::Tilted, |(f, _)| f)
}

/// Keeps `family`'s error in `s` and sets the other families' to none: the observed cube's
/// error (the grasp error), the observed fixture's error (the fixture error), the turn in the
/// grip (the tilt).
pub fn keep_only(s: &mut Scenario, family: ErrorFamily) {
    if family != ErrorFamily::GraspError {
        s.observed_position_error = [0.0; 3];
        s.observed_yaw_error = 0.0;
    }
    if let Some(f) = &mut s.fixture {
        if family != ErrorFamily::FixtureError {
            f.observed_xy_error = [0.0; 2];
            f.observed_yaw_error = 0.0;
        }
        if family != ErrorFamily::Tilted {
            f.grip_tilt = 0.0;
        }
        f.error_family = Some(family);
    }
}
