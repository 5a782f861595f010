//! The mix's weights (`[task.place.mix]`) and their rule.

use serde::{Deserialize, Serialize};

use crate::config::check::{Bounds, check, check_in};
use crate::config::error::ConfigError;

/// Which family's error a scenario of the mix carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorFamily {
    /// The pocket's observed pose is off (`place_fixture_error`).
    FixtureError,
    /// The cube is seen off, so the grasp is off-centre in the hand (`place_grasp_error`).
    GraspError,
    /// The cube turns in the grip once carried (`place_tilted`).
    Tilted,
}

impl ErrorFamily {
    /// Every family, in the order of the mix's weights.
    pub const ALL: [ErrorFamily; 3] = [Self::FixtureError, Self::GraspError, Self::Tilted];

    /// The name in presets and reports (`fixture_error`, `grasp_error`, `tilted`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::FixtureError => "fixture_error",
            Self::GraspError => "grasp_error",
            Self::Tilted => "tilted",
        }
    }

    /// The single-family preset whose error this is.
    pub fn preset(self) -> &'static str {
        match self {
            Self::FixtureError => "place_fixture_error",
            Self::GraspError => "place_grasp_error",
            Self::Tilted => "place_tilted",
        }
    }
}

impl std::fmt::Display for ErrorFamily {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The relative weights of the families in the mix (`[task.place.mix]`); a scenario carries
/// family `k` with probability `weight_k / Σ weights`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ErrorMix {
    pub fixture_error: f64,
    pub grasp_error: f64,
    pub tilted: f64,
}

impl Default for ErrorMix {
    /// An even mix.
    fn default() -> Self {
        Self {
            fixture_error: 1.0,
            grasp_error: 1.0,
            tilted: 1.0,
        }
    }
}

impl ErrorMix {
    /// The weights in the order of [`ErrorFamily::ALL`].
    pub fn weights(&self) -> [f64; 3] {
        [self.fixture_error, self.grasp_error, self.tilted]
    }

    /// The probability of each family, in the order of [`ErrorFamily::ALL`].
    pub fn probabilities(&self) -> [f64; 3] {
        let w = self.weights();
        let total: f64 = w.iter().sum();
        w.map(|x| x / total)
    }
}

/// Refuses weights that are not a mix: negative or not finite, or all zero; and a family
/// weighted in whose error the preset does not draw (`drawn`: whether each family of
/// [`ErrorFamily::ALL`] has an error of non-zero size).
pub(crate) fn check_error_mix(mix: &ErrorMix, drawn: [bool; 3]) -> Result<(), ConfigError> {
    for (family, w) in ErrorFamily::ALL.iter().zip(mix.weights()) {
        let field = match family {
            ErrorFamily::FixtureError => "task.place.mix.fixture_error",
            ErrorFamily::GraspError => "task.place.mix.grasp_error",
            ErrorFamily::Tilted => "task.place.mix.tilted",
        };
        check_in(w, field, Bounds::closed(0.0, 1000.0), "(a weight)")?;
    }
    check(
        mix.weights().iter().sum::<f64>() > 0.0,
        "task.place.mix",
        mix.weights(),
        "needs at least one weight above 0",
    )?;
    for ((family, w), drawn) in ErrorFamily::ALL.iter().zip(mix.weights()).zip(drawn) {
        let rule = match family {
            ErrorFamily::FixtureError => {
                "weights a family in whose error is never drawn: set task.place.observed_position_noise or observed_yaw_noise above 0"
            }
            ErrorFamily::GraspError => {
                "weights a family in whose error is never drawn: set randomization.observed_position_noise or observed_yaw_noise above 0"
            }
            ErrorFamily::Tilted => {
                "weights a family in whose error is never drawn: set task.place.grip_tilt's max above 0"
            }
        };
        check(
            w == 0.0 || drawn,
            &format!("task.place.mix.{family}"),
            w,
            rule,
        )?;
    }
    Ok(())
}
