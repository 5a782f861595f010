//! The scenario's turn of the cube in the grip, drawn from the generator the fixture's contact
//! conditions use ([`crate::scenario::fixture`]).

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::config::range::Range;

/// The angle the cube turns in the grip \[rad\]: a magnitude uniform in `grip_tilt` (none drawn
/// when its max is 0) and a random sign, two draws from `rng` in that order.
pub fn draw_grip_tilt(rng: &mut ChaCha8Rng, grip_tilt: Range) -> f64 {
    let [lo, hi] = grip_tilt;
    let magnitude = if hi > 0.0 {
        rng.random_range(lo..=hi)
    } else {
        0.0
    };
    let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    sign * magnitude
}
