//! The value axis of every chart: a plotters coordinate for `f64` that is drawable whatever
//! numbers the data hold.
//!
//! plotters' own `f64` axis computes its ticks in a loop that never ends for some ranges (a span
//! that overflows to infinity, as with 1.7e308 and a negative value; a span too small for the
//! magnitude of its ends) and maps far-away values to pixel offsets that overflow `i32`. [`Axis`]
//! replaces it:
//!
//! - [`Axis::new`] turns any two numbers into a usable range: NaN ends are dropped, ends are
//!   clamped to ±[`AXIS_LIMIT`] (so the span stays finite), and a range narrower than
//!   [`MIN_RELATIVE_SPAN`] of its magnitude (or [`MIN_ABSOLUTE_SPAN`]) is widened about its
//!   middle.
//! - [`Axis::ticks`] takes at most `max` values from a loop of at most `max` iterations.
//! - Mapping a value to a pixel pins it at most [`OVERSHOOT`] of the axis length past either end
//!   (NaN maps to the start), so pixel arithmetic never overflows and a line to a far-away point
//!   is no longer than the plot.

use std::ops::Range;

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};

/// Axis ends are clamped to ±this: the span of any two ends then stays finite.
pub const AXIS_LIMIT: f64 = 1e300;
/// The narrowest span, relative to the larger magnitude of the ends (below it, neighbouring
/// ticks would print the same and could not be told apart in `f64`).
pub const MIN_RELATIVE_SPAN: f64 = 1e-9;
/// The narrowest span in absolute terms (the tick step stays a normal `f64`).
pub const MIN_ABSOLUTE_SPAN: f64 = 1e-280;
/// At most this many ticks, whatever plotters asks for.
pub const MAX_TICKS: usize = 200;
/// A value outside the axis is drawn at most this fraction of the axis length past the end:
/// pinned just outside the plot, where it shows that something lies beyond.
pub const OVERSHOOT: f64 = 0.05;

/// A drawable `f64` range `lo < hi`, both finite (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axis {
    lo: f64,
    hi: f64,
}

impl Axis {
    /// The axis from `a` to `b` (in either order), made drawable: a NaN end is replaced by the
    /// other end (both NaN: 0 to 1), ends are clamped to ±[`AXIS_LIMIT`], and a too narrow range
    /// is widened about its middle.
    pub fn new(a: f64, b: f64) -> Self {
        let (a, b) = match (a.is_nan(), b.is_nan()) {
            (true, true) => (0.0, 1.0),
            (true, false) => (b, b),
            (false, true) => (a, a),
            (false, false) => (a, b),
        };
        let (a, b) = (
            a.clamp(-AXIS_LIMIT, AXIS_LIMIT),
            b.clamp(-AXIS_LIMIT, AXIS_LIMIT),
        );
        let (lo, hi) = (a.min(b), a.max(b));
        // Halves first: `hi - lo` itself could round up, `hi / 2 - lo / 2` cannot overflow.
        let mid = 0.5 * lo + 0.5 * hi;
        let half = 0.5 * hi - 0.5 * lo;
        let min_half = 0.5 * (MIN_RELATIVE_SPAN * lo.abs().max(hi.abs())).max(MIN_ABSOLUTE_SPAN);
        if half >= min_half {
            Self { lo, hi }
        } else {
            Self {
                lo: mid - min_half,
                hi: mid + min_half,
            }
        }
    }

    /// The axis over the finite `values` (non-finite ones are skipped), widened by `margin` of
    /// its span on each side and to at least `min_span`; 0 to 1 when no value is finite.
    pub fn fit(values: impl IntoIterator<Item = f64>, margin: f64, min_span: f64) -> Self {
        let (lo, hi) = min_max(values);
        let (lo, hi) = padded(lo, hi, margin, min_span);
        Self::new(lo, hi)
    }

    /// The lower end.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// The upper end.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// `(lo, hi)`.
    pub fn ends(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }

    /// At most `max` (and at most [`MAX_TICKS`]) round values in `[lo, hi]`, ascending: the
    /// multiples of the smallest step 1, 2 or 5 × 10ᵏ that keeps their number within `max`.
    pub fn ticks(&self, max: usize) -> Vec<f64> {
        let max = max.min(MAX_TICKS);
        if max == 0 {
            return Vec::new();
        }
        let step = self.tick_step(max);
        let mut first = (self.lo / step).ceil();
        // `lo / step` may round (or underflow to 0) below the true quotient.
        if first * step < self.lo {
            first += 1.0;
        }
        let mut ticks: Vec<f64> = Vec::with_capacity(max);
        // `first + i` is an integer far below 2⁵³ (the span is at least 1e-9 of the ends), so
        // every tick is a distinct exact multiple of `step`.
        for i in 0..max {
            let tick = (first + i as f64) * step;
            if tick > self.hi {
                break;
            }
            // No "-0" label.
            let tick = if tick == 0.0 { 0.0 } else { tick };
            if ticks.last() != Some(&tick) {
                ticks.push(tick);
            }
        }
        ticks
    }

    /// The tick step for at most `max ≥ 1` ticks.
    fn tick_step(&self, max: usize) -> f64 {
        let span = self.hi - self.lo;
        let rough = span / max as f64;
        let decade = 10f64.powi(rough.log10().floor() as i32);
        // `rough < 10·decade`, so the last candidate always fits: the span holds fewer than
        // `max` steps of it, hence at most `max` ticks.
        [1.0, 2.0, 5.0]
            .into_iter()
            .map(|m| m * decade)
            .find(|step| span / step < max as f64)
            .unwrap_or(10.0 * decade)
    }

    /// A tick label: as many decimals as a tenth of the span needs (trailing zeros dropped),
    /// in scientific notation beyond 10⁶ or below 10⁻³; empty for a non-finite value.
    pub fn label(&self, v: f64) -> String {
        if !v.is_finite() {
            return String::new();
        }
        let resolution = (self.hi - self.lo) / 10.0;
        let magnitude = self.lo.abs().max(self.hi.abs());
        if v == 0.0 || v.abs() < 1e-6 * resolution {
            return "0".into();
        }
        if !(1e-3..1e6).contains(&magnitude) {
            let digits = (magnitude.log10().floor() - resolution.log10().floor()).clamp(0.0, 12.0);
            let text = format!("{:.*e}", digits as usize, v);
            return match text.split_once('e') {
                Some((mantissa, exponent)) => format!("{}e{exponent}", trim_zeros(mantissa)),
                None => text,
            };
        }
        let decimals = (-resolution.log10().floor()).clamp(0.0, 12.0) as usize;
        trim_zeros(&format!("{v:.decimals$}")).to_string()
    }
}

/// `"2.500"` → `"2.5"`, `"3.000"` → `"3"`; integers are left alone.
fn trim_zeros(s: &str) -> &str {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        s
    }
}

impl From<Range<f64>> for Axis {
    fn from(r: Range<f64>) -> Self {
        Self::new(r.start, r.end)
    }
}

impl Ranged for Axis {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, (start, end): (i32, i32)) -> i32 {
        let t = (v - self.lo) / (self.hi - self.lo);
        let t = if t.is_nan() {
            0.0
        } else {
            t.clamp(-OVERSHOOT, 1.0 + OVERSHOOT)
        };
        let length = f64::from(end) - f64::from(start);
        // The same rounding as plotters' own axes, so charts look as before.
        let offset = if length >= 0.0 {
            (length * t + 1e-3).floor()
        } else {
            (length * t - 1e-3).ceil()
        };
        (f64::from(start) + offset) as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        self.ticks(hint.max_num_points())
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Axis {
    fn format_ext(&self, value: &f64) -> String {
        self.label(*value)
    }
}

/// `[lo, hi]` (each clamped to ±[`AXIS_LIMIT`]) widened by `margin` of its span and to at least
/// `min_span`; `[0, 1]` so widened when the bounds are not finite or not ordered (no value).
/// The result is finite for any input.
pub(crate) fn padded(lo: f64, hi: f64, margin: f64, min_span: f64) -> (f64, f64) {
    let (lo, hi) = if lo.is_finite() && hi.is_finite() && lo <= hi {
        (
            lo.clamp(-AXIS_LIMIT, AXIS_LIMIT),
            hi.clamp(-AXIS_LIMIT, AXIS_LIMIT),
        )
    } else {
        (0.0, 1.0)
    };
    // Halves first: `lo + hi` and `hi - lo` could overflow.
    let mid = 0.5 * lo + 0.5 * hi;
    let half = (0.5 * hi - 0.5 * lo).max(0.5 * min_span) * (1.0 + margin);
    (mid - half, mid + half)
}

/// The smallest and largest finite value (`(∞, −∞)` when there is none).
pub(crate) fn min_max(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ends that broke plotters' axis or are otherwise awkward.
    fn awkward_ranges() -> Vec<(f64, f64)> {
        let specials = [
            0.0,
            1.0,
            -1.0,
            0.3,
            1e-308,
            -1e-308,
            5e-324,
            1.7e308,
            -1e308,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e15,
            1e15 + 0.125,
            2048.0,
        ];
        let mut out = Vec::new();
        for a in specials {
            for b in specials {
                out.push((a, b));
            }
        }
        out
    }

    #[test]
    fn every_pair_of_ends_gives_a_finite_ordered_range_with_few_sorted_ticks_inside() {
        for (a, b) in awkward_ranges() {
            let axis = Axis::new(a, b);
            let (lo, hi) = axis.ends();
            assert!(
                lo.is_finite() && hi.is_finite() && lo < hi,
                "{a} {b}: {lo} {hi}"
            );
            assert!((hi - lo).is_finite(), "{a} {b}: span overflows");
            for max in [0, 1, 2, 5, 6, 10, 60, 10_000] {
                let ticks = axis.ticks(max);
                assert!(
                    ticks.len() <= max.min(MAX_TICKS),
                    "{a} {b} {max}: {ticks:?}"
                );
                assert!(ticks.windows(2).all(|w| w[0] < w[1]), "{a} {b}: {ticks:?}");
                assert!(
                    ticks.iter().all(|t| (lo..=hi).contains(t)),
                    "{a} {b}: {ticks:?}"
                );
                if max >= 2 {
                    assert!(!ticks.is_empty(), "{a} {b} {max}: no tick");
                }
                for t in &ticks {
                    assert!(!axis.label(*t).is_empty(), "{a} {b}: label of {t}");
                }
            }
        }
    }

    #[test]
    fn ordinary_ranges_keep_round_ticks_and_short_labels() {
        let axis = Axis::new(-0.03, 1.03);
        assert_eq!(
            axis.ticks(6),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        let labels: Vec<String> = axis.ticks(6).iter().map(|t| axis.label(*t)).collect();
        assert_eq!(labels, ["0", "0.2", "0.4", "0.6", "0.8", "1"]);
        let axis = Axis::new(0.0, 108.0);
        assert_eq!(axis.ticks(6), vec![0.0, 20.0, 40.0, 60.0, 80.0, 100.0]);
        let axis = Axis::new(-1e308, 1.7e308);
        let labels: Vec<String> = axis.ticks(5).iter().map(|t| axis.label(*t)).collect();
        assert!(
            labels.iter().all(|l| l == "0" || l.contains('e')),
            "{labels:?}"
        );
    }

    #[test]
    fn a_single_value_gets_a_range_around_it() {
        let axis = Axis::new(3.25, 3.25);
        assert!(axis.lo() < 3.25 && 3.25 < axis.hi());
        let axis = Axis::fit([f64::NAN, f64::INFINITY], 0.1, 1.0);
        assert!(axis.lo() < axis.hi());
    }

    #[test]
    fn any_value_maps_to_a_pixel_near_the_axis() {
        let axis = Axis::new(-1e308, 1.7e308);
        let small = Axis::new(0.0, 1e-300);
        for v in [
            0.0,
            1.7e308,
            -f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e-308,
        ] {
            for a in [axis, small] {
                for limit in [(60, 1000), (900, 20)] {
                    let p = a.map(&v, limit);
                    let (lo, hi) = (limit.0.min(limit.1), limit.0.max(limit.1));
                    let past = (OVERSHOOT * f64::from(hi - lo)).ceil() as i32 + 1;
                    assert!(p >= lo - past && p <= hi + past, "{v} → {p}");
                }
            }
        }
        assert_eq!(Axis::new(0.0, 10.0).map(&5.0, (0, 100)), 50);
        assert_eq!(Axis::new(0.0, 10.0).map(&5.0, (100, 0)), 50);
    }
}
