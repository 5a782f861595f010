//! The scenario's family in the mix, from a generator of its own (the rest of the scenario is
//! drawn as without the mix), and the errors it keeps.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::scenario::error_mix::settings::{ErrorFamily, ErrorMix};
use crate::scenario::fixture::draw::FixturePose;

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

/// Keeps `family`'s error and sets the other families' to none: the observed cube's error
/// (`cube_error`: position \[m\] and yaw \[rad\]; the grasp error), the observed fixture's
/// error (the fixture error), the turn in the grip (the tilt); records the family in `fixture`.
pub fn keep_only(
    family: ErrorFamily,
    cube_error: (&mut [f64; 3], &mut f64),
    fixture: &mut FixturePose,
) {
    if family != ErrorFamily::GraspError {
        *cube_error.0 = [0.0; 3];
        *cube_error.1 = 0.0;
    }
    if family != ErrorFamily::FixtureError {
        fixture.observed_xy_error = [0.0; 2];
        fixture.observed_yaw_error = 0.0;
    }
    if family != ErrorFamily::Tilted {
        fixture.grip_tilt = 0.0;
    }
    fixture.error_family = Some(family);
}
