//! The checks every config rule is written with: a condition with its field, value and rule
//! ([`check`]), a number within [`Bounds`] ([`check_in`]) and a `[min, max]` range whose ends lie
//! within bounds ([`check_range`]). A bound is written once, as a [`Bounds`] value: the check and
//! the refusal's text are both made from it, so a message cannot state other bounds than the
//! ones checked. A leaf: the validation files import it, it imports nothing of theirs.

use crate::config::error::ConfigError;

/// `Ok` when `ok`, else the refusal naming `field`, its `value` and the `rule`.
pub(crate) fn check(
    ok: bool,
    field: &str,
    value: impl std::fmt::Debug,
    rule: &'static str,
) -> Result<(), ConfigError> {
    if ok {
        Ok(())
    } else {
        Err(ConfigError::Invalid {
            field: field.to_string(),
            value: format!("{value:?}"),
            rule: rule.into(),
        })
    }
}

/// An interval a setting must lie in, in the setting's unit: each end closed, open or absent
/// (±∞). Written in a refusal as `[0, 0.05] s`, `(0, inf) N` or `[-3.141592653589793, inf) rad`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The lowest value (−∞ for none).
    pub low: f64,
    /// The highest value (+∞ for none).
    pub high: f64,
    /// Whether `low` itself is refused.
    pub low_open: bool,
    /// Whether `high` itself is refused.
    pub high_open: bool,
    /// The unit the ends are in (`"m"`, `"rad/s"`; empty for a plain number).
    pub unit: &'static str,
}

impl Bounds {
    /// `[low, high]`.
    pub const fn closed(low: f64, high: f64) -> Bounds {
        Bounds {
            low,
            high,
            low_open: false,
            high_open: false,
            unit: "",
        }
    }

    /// `(low, high]`.
    pub const fn above_to(low: f64, high: f64) -> Bounds {
        Bounds {
            low_open: true,
            ..Bounds::closed(low, high)
        }
    }

    /// `[low, high)`.
    pub const fn from_below(low: f64, high: f64) -> Bounds {
        Bounds {
            high_open: true,
            ..Bounds::closed(low, high)
        }
    }

    /// `[low, inf)`.
    pub const fn at_least(low: f64) -> Bounds {
        Bounds::from_below(low, f64::INFINITY)
    }

    /// `(low, inf)`.
    pub const fn above(low: f64) -> Bounds {
        Bounds {
            low_open: true,
            ..Bounds::at_least(low)
        }
    }

    /// The same bounds in `unit`.
    pub const fn unit(self, unit: &'static str) -> Bounds {
        Bounds { unit, ..self }
    }

    /// Whether `value` lies within (NaN never does).
    pub fn contains(&self, value: f64) -> bool {
        let above_low = if self.low_open {
            value > self.low
        } else {
            value >= self.low
        };
        let below_high = if self.high_open {
            value < self.high
        } else {
            value <= self.high
        };
        above_low && below_high
    }
}

impl std::fmt::Display for Bounds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let open = if self.low_open { '(' } else { '[' };
        let close = if self.high_open { ')' } else { ']' };
        write!(f, "{open}{}, {}{close}", self.low, self.high)?;
        if !self.unit.is_empty() {
            write!(f, " {}", self.unit)?;
        }
        Ok(())
    }
}

/// The bounds of a `[min, max]` range a sampler draws from, with the reason for them: both ends
/// finite (a draw between `1e308` and its square overflows, and one between `-1e308` and
/// `1e308` has no width a generator can scale), each the bound the sampler and the scene need.
/// Every range of every table is checked against one (`check_range`); a bound with an end at
/// ±∞ cannot be made (a constant one fails to compile, another one panics when it is made).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RangeBounds {
    /// Where both ends must lie.
    pub bounds: Bounds,
    /// Why, as the refusal states it after the bounds (`(the FR3's reach …)`).
    pub reason: &'static str,
}

impl RangeBounds {
    /// `bounds` for a range, with its `reason`; both ends of `bounds` must be finite.
    pub const fn new(bounds: Bounds, reason: &'static str) -> RangeBounds {
        assert!(
            bounds.low.is_finite() && bounds.high.is_finite(),
            "a range's bounds must be finite: the sampler draws between its ends"
        );
        RangeBounds { bounds, reason }
    }
}

/// The farthest a drawn position on the table may lie from the point under the base \[m\]:
/// a sector's radius (the cube's, the fixture's, the second cube's).
pub const MAX_TABLE_RADIUS: f64 = 1.0;

/// A sector's radius on the table \[m\], from the point under the base origin.
pub(crate) const SECTOR_RADIUS: RangeBounds = RangeBounds::new(
    Bounds::closed(0.0, MAX_TABLE_RADIUS).unit("m"),
    "(the FR3 reaches 0.622 m from its shoulder: no mount reaches a cube 1 m from the base)",
);

/// A sector's angle about the vertical, from the base's heading \[rad\].
pub(crate) const SECTOR_ANGLE: RangeBounds = RangeBounds::new(
    Bounds::closed(-std::f64::consts::PI, std::f64::consts::PI).unit("rad"),
    "(one turn about the base: -π and π are both straight behind it)",
);

/// A number a setting holds: a float or a count, shown in a refusal as it was written.
pub trait SettingNumber: Copy + std::fmt::Debug {
    /// The value on the real line, to compare with [`Bounds`].
    fn as_f64(self) -> f64;
}

impl SettingNumber for f64 {
    fn as_f64(self) -> f64 {
        self
    }
}

impl SettingNumber for f32 {
    fn as_f64(self) -> f64 {
        f64::from(self)
    }
}

impl SettingNumber for usize {
    fn as_f64(self) -> f64 {
        self as f64
    }
}

impl SettingNumber for u32 {
    fn as_f64(self) -> f64 {
        f64::from(self)
    }
}

impl SettingNumber for u64 {
    fn as_f64(self) -> f64 {
        self as f64
    }
}

/// The rule a refusal states for a number outside `bounds`: `must be in [0, 0.05] s`, then
/// `note` (a default, a reason) when it is not empty.
pub fn bounds_rule(bounds: &Bounds, note: &str) -> String {
    if note.is_empty() {
        format!("must be in {bounds}")
    } else {
        format!("must be in {bounds} {note}")
    }
}

/// `Ok` when `value` lies within `bounds`, else the refusal naming `field`, the value and both
/// bounds (then `note`).
pub fn check_in(
    value: impl SettingNumber,
    field: &str,
    bounds: Bounds,
    note: &'static str,
) -> Result<(), ConfigError> {
    if bounds.contains(value.as_f64()) {
        Ok(())
    } else {
        Err(ConfigError::Invalid {
            field: field.to_string(),
            value: format!("{value:?}"),
            rule: bounds_rule(&bounds, note).into(),
        })
    }
}

/// A `[min, max]` range (a [`crate::config::Range`] or a pair of counts): finite, ordered, and
/// both ends within `bounds`, whose ends are finite ([`RangeBounds`]); the refusal names the
/// field, the value, the bounds and their reason.
pub(crate) fn check_range<N: SettingNumber>(
    range: &[N; 2],
    field: &str,
    bounds: RangeBounds,
) -> Result<(), ConfigError> {
    let [min, max] = range.map(N::as_f64);
    let RangeBounds { bounds, reason } = bounds;
    check(
        min.is_finite() && max.is_finite(),
        field,
        range,
        "must be finite",
    )?;
    check(min <= max, field, range, "min must not exceed max")?;
    if bounds.contains(min) && bounds.contains(max) {
        return Ok(());
    }
    Err(ConfigError::Invalid {
        field: field.to_string(),
        value: format!("{range:?}"),
        rule: format!("both ends must be in {bounds} {reason}").into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_written_as_they_are_checked() {
        let b = Bounds::above_to(0.0, 0.05).unit("s");
        assert_eq!(b.to_string(), "(0, 0.05] s");
        assert!(!b.contains(0.0) && b.contains(0.05) && !b.contains(0.050001));
        let b = Bounds::at_least(-std::f64::consts::PI).unit("rad");
        assert_eq!(b.to_string(), "[-3.141592653589793, inf) rad");
        assert!(b.contains(-std::f64::consts::PI) && !b.contains(-3.2));
        assert!(!Bounds::above(0.0).contains(f64::NAN));
        assert!(!Bounds::above(0.0).contains(f64::INFINITY));
    }

    #[test]
    fn a_refusal_names_the_field_the_value_and_both_bounds() {
        let e = check_in(100_001usize, "task.max_steps", Bounds::closed(1.0, 1e5), "").unwrap_err();
        assert_eq!(
            e.to_string(),
            "task.max_steps = 100001: must be in [1, 100000]"
        );
        let e = check_range(&[-3.5, 1.0], "randomization.angle", SECTOR_ANGLE).unwrap_err();
        assert_eq!(
            e.to_string(),
            "randomization.angle = [-3.5, 1.0]: both ends must be in [-3.141592653589793, \
             3.141592653589793] rad (one turn about the base: -π and π are both straight behind it)"
        );
        let e = check_range(&[0.3, 1e308], "task.stack.base_radius", SECTOR_RADIUS).unwrap_err();
        assert!(
            e.to_string().starts_with(
                "task.stack.base_radius = [0.3, 1e308]: both ends must be in [0, 1] m (the FR3"
            ),
            "{e}"
        );
    }
}
