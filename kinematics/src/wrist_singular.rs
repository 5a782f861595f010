//! Choosing θ6 where the wrist is singular (θ5 = 0 or π).
//!
//! There joint 6 turns about an axis parallel to joints 2, 3 and 4, so four parallel joints
//! serve three planar degrees of freedom and θ6 is free: any θ6 works, with θ2, θ3, θ4 solved
//! after it, as long as the elbow can still reach. The origin of frame 4 lies d5 from the
//! flange axis, in a direction that turns with θ6; its squared distance from joint 2 (in the
//! plane of joints 2 … 4, frame 1) is therefore `mean + amplitude·cos(θ6 − phase)`, and the
//! elbow reaches for `|θ6 − phase|` within an interval. Keeping θ6 at a fixed value (0 or the
//! caller's seed) regardless of that interval is what made reachable poses "out of reach".

use std::f64::consts::{FRAC_PI_2, PI};

use crate::angles::wrap_pi;

/// How far inside the reaching arc a θ6 moved onto it is placed \[rad\], so that the elbow is
/// not exactly straight or folded (where rounding could push it just out of reach).
const ARC_MARGIN: f64 = 1e-6;
/// Values of θ6 spread over each half of the reaching arc, tried when the preferred one puts
/// a joint outside its limits.
const SPREAD: usize = 8;
/// `cos` bounds this far beyond ±1 are treated as rounding (a pose exactly at the reach).
const COS_SLACK: f64 = 1e-9;

/// θ6 values \[rad\] for which the elbow reaches, best first; empty if none does.
///
/// `reach_sq(θ6)` is the squared distance \[m²\] the elbow must span for that θ6 (sinusoidal in
/// θ6 at a singular wrist) and `reach_sq_range` the interval \[m²\] the elbow can span. First
/// comes `seed` \[rad\] if it reaches, else the reaching θ6 nearest to it (moved [`ARC_MARGIN`]
/// inside the arc); then θ6 values spread
/// over the reaching arc, nearest to `seed` first, for the caller to try when the first one puts
/// θ4 or θ6 outside its limits. A non-finite seed counts as 0.
pub fn singular_wrist_q6_candidates(
    seed: f64,
    reach_sq: impl Fn(f64) -> f64,
    reach_sq_range: (f64, f64),
) -> Vec<f64> {
    let seed = if seed.is_finite() { seed } else { 0.0 };
    // reach_sq(θ6) = mean + b·cos θ6 + c·sin θ6, read off three samples.
    let (at_0, at_90, at_180) = (reach_sq(0.0), reach_sq(FRAC_PI_2), reach_sq(PI));
    let mean = 0.5 * (at_0 + at_180);
    let (b, c) = (0.5 * (at_0 - at_180), at_90 - mean);
    let amplitude = b.hypot(c);
    let phase = c.atan2(b);
    let (lowest, highest) = reach_sq_range;
    if !(mean.is_finite() && amplitude.is_finite()) {
        return Vec::new();
    }

    // The reaching arc: |θ6 − phase| ∈ [near, far], each bound moved inside by the margin
    // where it is a reach limit rather than 0 or π.
    // The seed is kept where it reaches: `reaches` is the unshrunk arc.
    let (near, far, reaches) = if amplitude <= 1e-12 * mean.abs().max(1.0) {
        if mean < lowest * (1.0 - COS_SLACK) || mean > highest * (1.0 + COS_SLACK) {
            return Vec::new();
        }
        (0.0, PI, (0.0, PI))
    } else {
        // reach_sq ≤ highest ⇔ cos δ ≤ cos_max;  reach_sq ≥ lowest ⇔ cos δ ≥ cos_min.
        let cos_max = (highest - mean) / amplitude;
        let cos_min = (lowest - mean) / amplitude;
        if cos_max < -1.0 - COS_SLACK || cos_min > 1.0 + COS_SLACK || cos_min > cos_max {
            return Vec::new();
        }
        let near_limit = cos_max.clamp(-1.0, 1.0).acos();
        let far_limit = cos_min.clamp(-1.0, 1.0).acos();
        let margin = ARC_MARGIN.min(0.25 * (far_limit - near_limit));
        let near = if cos_max < 1.0 {
            near_limit + margin
        } else {
            0.0
        };
        let far = if cos_min > -1.0 {
            far_limit - margin
        } else {
            PI
        };
        (near, far.max(near), (near_limit, far_limit))
    };

    let from_seed = wrap_pi(seed - phase);
    let preferred = if (reaches.0..=reaches.1).contains(&from_seed.abs()) {
        seed
    } else {
        let side = if from_seed < 0.0 { -1.0 } else { 1.0 };
        phase + side * from_seed.abs().clamp(near, far)
    };
    let mut spread: Vec<f64> = (0..SPREAD)
        .flat_map(|k| {
            let offset = near + (far - near) * (k as f64 + 0.5) / SPREAD as f64;
            [phase + offset, phase - offset]
        })
        .collect();
    spread.sort_by(|x, y| {
        let distance = |q6: f64| wrap_pi(q6 - seed).abs();
        distance(*x).total_cmp(&distance(*y))
    });
    let mut candidates = Vec::with_capacity(1 + spread.len());
    candidates.push(preferred);
    candidates.extend(spread);
    candidates
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reach that is 0.25 + 0.05·cos(θ6 − 1).
    fn reach(q6: f64) -> f64 {
        0.25 + 0.05 * (q6 - 1.0).cos()
    }

    #[test]
    fn a_seed_that_reaches_is_kept() {
        let candidates = singular_wrist_q6_candidates(0.9, reach, (0.0, 1.0));
        assert!((candidates[0] - 0.9).abs() < 1e-12, "{candidates:?}");
    }

    #[test]
    fn a_seed_that_does_not_reach_moves_to_the_nearest_reaching_value() {
        // Reaches only where cos(θ6 − 1) ≤ 0, i.e. |θ6 − 1| ≥ π/2; the seed 1.2 is 0.2 from 1.
        let candidates = singular_wrist_q6_candidates(1.2, reach, (0.0, 0.25));
        let first = candidates[0];
        assert!(
            (first - (1.0 + FRAC_PI_2 + ARC_MARGIN)).abs() < 1e-9,
            "{first}"
        );
        assert!(candidates.iter().all(|&q6| reach(q6) <= 0.25));
    }

    #[test]
    fn no_candidate_when_no_q6_reaches() {
        assert!(singular_wrist_q6_candidates(0.0, reach, (0.31, 1.0)).is_empty());
        assert!(singular_wrist_q6_candidates(0.0, reach, (0.0, 0.19)).is_empty());
    }
}
