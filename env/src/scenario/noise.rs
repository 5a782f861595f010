//! The draws scenarios are made of: the one Gaussian draw every scenario error is made of, and
//! a point uniform over a sector of the table (the cube's and the fixture's positions).

use rand::Rng;
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

/// A point \[m\] uniform over the area of the sector `radius` \[m\] × `angle` \[rad\] about the
/// base's z axis, in the table frame: radius ~ sqrt(U(r0², r1²)), then angle ~ U(a0, a1) (two
/// draws from `rng`, in that order).
pub fn uniform_in_sector(rng: &mut ChaCha8Rng, radius: [f64; 2], angle: [f64; 2]) -> [f64; 2] {
    let r = rng
        .random_range(radius[0].powi(2)..=radius[1].powi(2))
        .sqrt();
    let a = rng.random_range(angle[0]..=angle[1]);
    [r * a.cos(), r * a.sin()]
}
