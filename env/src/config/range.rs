//! A closed interval of a setting, `[min, max]`.

/// A closed interval `[min, max]`.
pub type Range = [f64; 2];
