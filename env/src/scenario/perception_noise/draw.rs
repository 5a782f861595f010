//! The scenario's perception errors, drawn from the generator the cube's start is drawn with.

use rand_chacha::ChaCha8Rng;

use crate::scenario::noise::gauss;

/// The error on the observed position, table frame \[m\] (x, y drawn, z 0: the cube's height is
/// known), and on the observed yaw \[rad\]: three Gaussian draws from `rng` in that order, with
/// standard deviations `position` \[m\] and `yaw` \[rad\] (none drawn for a zero level).
pub fn draw_perception_errors(rng: &mut ChaCha8Rng, position: f64, yaw: f64) -> ([f64; 3], f64) {
    // Perception noise lies on the table plane: the cube's height is known.
    let position_error = [gauss(rng, position), gauss(rng, position), 0.0];
    let yaw_error = gauss(rng, yaw);
    (position_error, yaw_error)
}
