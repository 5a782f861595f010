//! Helpers shared by the kinematics tests: seeded random configurations.
#![allow(dead_code)]

use fairgrasp_kinematics::ArmModel;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A seeded generator, so every test run draws the same samples.
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A configuration drawn uniformly within the joint limits \[rad\].
pub fn random_in_limits(model: &ArmModel, rng: &mut ChaCha8Rng) -> [f64; 6] {
    model.joints.map(|j| rng.random_range(j.lower..=j.upper))
}

/// Largest absolute difference between two joint vectors \[rad\].
pub fn max_abs_diff(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}
