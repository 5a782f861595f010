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

/// A `[min, max]` range: finite, ordered, and not below `lowest`.
pub(crate) fn check_range(
    range: &Range,
    field: &'static str,
    lowest: f64,
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
    check(range[0] >= lowest, field, range, "must not be negative")
}
