//! The one Gaussian draw every scenario error is made of.

use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// A draw from N(0, σ²) with `rng`; 0 without noise (`sigma` ≤ 0), and then no draw is taken,
/// so switching a noise off leaves the draws after it unchanged.
pub fn gauss(rng: &mut ChaCha8Rng, sigma: f64) -> f64 {
    match Normal::new(0.0, sigma) {
        Ok(normal) if sigma > 0.0 => normal.sample(rng),
        _ => 0.0,
    }
}
