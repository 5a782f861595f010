//! A control's tunable parameters: what `fairgrasp tune` may set, within what the control
//! accepts, and the values a tuning wrote.

use std::collections::BTreeMap;

/// Values of a control's parameters by name (a switch as 0 or 1).
pub type ParamValues = BTreeMap<String, f64>;

/// How a parameter is searched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Uniformly between its bounds.
    Linear,
    /// Uniformly in its logarithm (a positive quantity spanning decades).
    Log,
    /// Off (0) or on (1): searched as a number in [0, 1], on above one half.
    Switch,
}

/// One tunable parameter of a control.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Param {
    /// Its name in `--param`, the trial CSV and a tuned fragment.
    pub name: &'static str,
    /// Its unit, as a doc comment writes it (`m/s`, `N`; empty for a switch).
    pub unit: &'static str,
    /// What the control accepts (the preset's rule for the same setting).
    pub accepts: [f64; 2],
    /// The range `tune` searches by default (within `accepts`).
    pub range: [f64; 2],
    pub scale: Scale,
    /// What it does, in a few words.
    pub doc: &'static str,
}

impl Param {
    /// Is `value` one the control accepts?
    pub fn accepts(&self, value: f64) -> bool {
        value.is_finite() && value >= self.accepts[0] && value <= self.accepts[1]
    }

    /// `value` as `[lo, hi]` maps it to [0, 1] (through the logarithm for a log scale).
    pub fn to_unit(&self, value: f64, [lo, hi]: [f64; 2]) -> f64 {
        match self.scale {
            Scale::Log => (value / lo).ln() / (hi / lo).ln(),
            Scale::Linear | Scale::Switch => (value - lo) / (hi - lo),
        }
    }

    /// The value at `u` in [0, 1] of `[lo, hi]` (clamped into it; a switch is 0 or 1).
    pub fn from_unit(&self, u: f64, [lo, hi]: [f64; 2]) -> f64 {
        let u = u.clamp(0.0, 1.0);
        match self.scale {
            Scale::Log => lo * (hi / lo).powf(u),
            Scale::Linear => lo + u * (hi - lo),
            Scale::Switch => {
                if u > 0.5 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}
