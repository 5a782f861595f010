//! Checking a joint stream against the FR3's limits before it is written or played: joint
//! limits, velocity, acceleration and the driver's largest step per sample. A violation is
//! reported with the first offending sample, joint and value; nothing is ever clipped.

use std::fmt;

use crate::stream::limits::{PERIOD_RANGE_SEC, StreamLimits};

/// Which limit a sample crosses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// The joint angle is outside the soft limits (or not finite).
    Position,
    /// The change since the previous sample exceeds the driver's largest step.
    Step,
    /// The velocity (change over one period) exceeds the joint's limit.
    Velocity,
    /// The acceleration (second difference over the period²) exceeds the limit; the stream
    /// starts and ends at rest (the blocking move before it, the hold after it).
    Acceleration,
}

/// The first sample of a stream that crosses a limit.
#[derive(Clone, Debug, PartialEq)]
pub struct StreamViolation {
    /// Index of the sample (0 = the start).
    pub sample: usize,
    /// Time of the sample from the start \[s\].
    pub time_sec: f64,
    /// Joint number, 1 … 6 (FAIRINO's j1 … j6).
    pub joint: usize,
    pub quantity: Quantity,
    /// The offending value: rad, rad (step), rad/s or rad/s².
    pub value: f64,
    /// The limit it crosses, in the same unit (for a position: the limit it is beyond).
    pub limit: f64,
}

impl fmt::Display for StreamViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (s, t, j) = (self.sample, self.time_sec, self.joint);
        let (v, l) = (self.value, self.limit);
        match self.quantity {
            Quantity::Position if !v.is_finite() => {
                write!(f, "sample {s} (t = {t:.3} s), j{j}: {v} is not a number")
            }
            Quantity::Position => write!(
                f,
                "sample {s} (t = {t:.3} s), j{j}: {:.3}° is beyond the soft limit {:.1}° \
                 (docs/FR3.md)",
                v.to_degrees(),
                l.to_degrees()
            ),
            Quantity::Step => write!(
                f,
                "sample {s} (t = {t:.3} s), j{j}: moves {:.3}° from the previous sample, more \
                 than the {:.2}° per sample the FAIRINO driver accepts",
                v.to_degrees(),
                l.to_degrees()
            ),
            Quantity::Velocity => write!(
                f,
                "sample {s} (t = {t:.3} s), j{j}: velocity {v:.3} rad/s ({:.1}°/s) exceeds the \
                 FR3's {l:.2} rad/s (docs/FR3.md)",
                v.to_degrees()
            ),
            Quantity::Acceleration => write!(
                f,
                "sample {s} (t = {t:.3} s), j{j}: acceleration {v:.2} rad/s² exceeds \
                 {l:.1} rad/s² (fairgrasp's limit for the FR3, docs/FR3.md)"
            ),
        }
    }
}

impl std::error::Error for StreamViolation {}

/// Relative slack for values computed from written samples (decimal rounding of degrees).
const SLACK: f64 = 1e-6;

/// Checks `joints` \[rad\], one sample per `period` \[s\], against `limits`: every joint within its
/// soft limits, every step within `max_step`, every velocity within the joint's limit and every
/// acceleration within `max_acceleration`, the stream taken as starting and ending at rest.
/// Returns the first violation in sample order (position, step, velocity, then acceleration
/// at one sample; joints in order). Panics if `period` is outside [`PERIOD_RANGE_SEC`]: callers
/// check it first, naming their flag or field.
pub fn check_stream(
    joints: &[[f64; 6]],
    period: f64,
    limits: &StreamLimits,
) -> Result<(), StreamViolation> {
    assert!(PERIOD_RANGE_SEC.contains(&period), "period {period} s");
    let violation = |sample: usize, joint: usize, quantity, value, limit| StreamViolation {
        sample,
        time_sec: sample as f64 * period,
        joint: joint + 1,
        quantity,
        value,
        limit,
    };
    let at = |n: isize| joints[n.clamp(0, joints.len() as isize - 1) as usize];
    for (n, q) in joints.iter().enumerate() {
        for (i, &v) in q.iter().enumerate() {
            let (lo, hi) = (limits.lower[i], limits.upper[i]);
            if !v.is_finite() || v < lo - 1e-9 || v > hi + 1e-9 {
                let limit = if v < lo { lo } else { hi };
                return Err(violation(n, i, Quantity::Position, v, limit));
            }
        }
        if n == 0 {
            continue;
        }
        let (prev, before) = (at(n as isize - 1), at(n as isize - 2));
        for i in 0..6 {
            let step = (q[i] - prev[i]).abs();
            if step > limits.max_step * (1.0 + SLACK) {
                return Err(violation(n, i, Quantity::Step, step, limits.max_step));
            }
            let velocity = (q[i] - prev[i]) / period;
            if velocity.abs() > limits.max_velocity[i] * (1.0 + SLACK) {
                let limit = limits.max_velocity[i];
                return Err(violation(n, i, Quantity::Velocity, velocity, limit));
            }
            let acceleration = (q[i] - 2.0 * prev[i] + before[i]) / (period * period);
            if acceleration.abs() > limits.max_acceleration * (1.0 + SLACK) + 1e-3 {
                let limit = limits.max_acceleration;
                return Err(violation(n, i, Quantity::Acceleration, acceleration, limit));
            }
        }
    }
    // Coming to rest after the last sample.
    if let [.., before, last] = joints {
        for i in 0..6 {
            let acceleration = (before[i] - last[i]) / (period * period);
            if acceleration.abs() > limits.max_acceleration * (1.0 + SLACK) + 1e-3 {
                let (n, limit) = (joints.len(), limits.max_acceleration);
                return Err(violation(n, i, Quantity::Acceleration, acceleration, limit));
            }
        }
    }
    Ok(())
}

/// The largest values a stream reaches, over all joints and samples (the stream taken as
/// starting and ending at rest, as in [`check_stream`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Peaks {
    /// Largest change of a joint between two samples \[deg\].
    pub step_deg: f64,
    /// Largest joint speed \[rad/s\].
    pub velocity_rad_s: f64,
    /// Largest joint acceleration \[rad/s²\].
    pub acceleration_rad_s2: f64,
}

/// The peaks of `joints` \[rad\] sampled every `period` \[s\].
pub fn peaks(joints: &[[f64; 6]], period: f64) -> Peaks {
    let n = joints.len() as isize;
    let at = |k: isize| joints[k.clamp(0, n - 1) as usize];
    let mut p = Peaks::default();
    for k in 1..=n {
        let (q, prev, before) = (at(k), at(k - 1), at(k - 2));
        for i in 0..6 {
            let step = (q[i] - prev[i]).abs();
            p.step_deg = p.step_deg.max(step.to_degrees());
            p.velocity_rad_s = p.velocity_rad_s.max(step / period);
            let a = (q[i] - 2.0 * prev[i] + before[i]).abs() / (period * period);
            p.acceleration_rad_s2 = p.acceleration_rad_s2.max(a);
        }
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> StreamLimits {
        StreamLimits::of(&fairgrasp_kinematics::fairino::fr3())
    }

    /// `n` samples every `period` of j2 speeding up at 5 rad/s² to `speed` \[rad/s\] and slowing
    /// down at 5 rad/s² to rest at the last sample.
    fn ramp(speed: f64, period: f64, n: usize) -> Vec<[f64; 6]> {
        let mut q = [0.0, -3.0, 1.5, -2.0, -1.57, 0.0];
        (0..n)
            .map(|k| {
                let out = q;
                let v = speed
                    .min(5.0 * (k + 1) as f64 * period)
                    .min(5.0 * n.saturating_sub(k + 2) as f64 * period);
                q[1] += v * period;
                out
            })
            .collect()
    }

    #[test]
    fn a_gentle_ramp_passes_and_a_fast_one_is_refused_at_its_first_fast_sample() {
        let l = limits();
        check_stream(&ramp(1.0, 0.008, 400), 0.008, &l).expect("1 rad/s at 8 ms is fine");
        // 2.5 rad/s at 8 ms is 1.15° per sample: the step guard (1°) trips first, at the first
        // sample whose step exceeds 1°, while the FR3's 3.15 rad/s is not yet reached.
        let e = check_stream(&ramp(2.5, 0.008, 400), 0.008, &l).unwrap_err();
        assert_eq!((e.joint, e.quantity), (2, Quantity::Step));
        let first = (e.value.to_degrees() - 1.0) / 1.0;
        assert!(first > 0.0 && first < 0.05, "the first step past 1°: {e}");
        let text = e.to_string();
        assert!(text.contains("j2") && text.contains(&format!("sample {}", e.sample)));
    }

    #[test]
    fn a_jump_an_excess_acceleration_and_a_position_beyond_the_limit_are_named() {
        let l = limits();
        let mut q = ramp(0.5, 0.004, 100);
        q[50][4] += 0.5f64.to_radians(); // 0.5° in one 4 ms sample: 2.2 rad/s velocity jump
        let e = check_stream(&q, 0.004, &l).unwrap_err();
        assert_eq!(
            (e.sample, e.joint, e.quantity),
            (50, 5, Quantity::Acceleration)
        );
        let mut q = ramp(0.5, 0.008, 100);
        q[70][0] = 176f64.to_radians(); // j1's soft limit is ±175°
        let e = check_stream(&q, 0.008, &l).unwrap_err();
        assert_eq!((e.sample, e.joint, e.quantity), (70, 1, Quantity::Position));
        assert!(e.to_string().contains("175.0°"), "{e}");
        q[70][0] = f64::NAN;
        let e = check_stream(&q, 0.008, &l).unwrap_err();
        assert!(e.to_string().contains("not a number"), "{e}");
    }

    #[test]
    fn a_stream_that_stops_dead_is_refused_at_its_end() {
        // Moving at 0.5 rad/s on the last sample: stopping within one 8 ms period is 62 rad/s².
        let q = &ramp(0.5, 0.008, 200)[..100];
        let e = check_stream(q, 0.008, &limits()).unwrap_err();
        assert_eq!((e.sample, e.quantity), (100, Quantity::Acceleration));
    }
}
