//! The two checks every config rule is written with: a condition with its field, value and rule,
//! and a `[min, max]` range. A leaf: the validation files import it, it imports nothing of
//! theirs.

use crate::config::error::ConfigError;
use crate::config::range::Range;

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
            rule,
        })
    }
}

/// The lowest value a range accepts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Lowest {
    /// 0: a distance, a friction, a scale.
    Zero,
    /// −π: an angle about the vertical.
    MinusPi,
}

/// A `[min, max]` range: finite, ordered, and not below `lowest` (the message states it).
pub(crate) fn check_range(
    range: &Range,
    field: &'static str,
    lowest: Lowest,
) -> Result<(), ConfigError> {
    check(
        range.iter().all(|v| v.is_finite()),
        field,
        range,
        "must be finite",
    )?;
    check(
        range[0] <= range[1],
        field,
        range,
        "min must not exceed max",
    )?;
    let (bound, rule) = match lowest {
        Lowest::Zero => (0.0, "must not be negative"),
        Lowest::MinusPi => (
            -std::f64::consts::PI,
            "must not start below -π (-3.141592653589793) rad",
        ),
    };
    check(range[0] >= bound, field, range, rule)
}
