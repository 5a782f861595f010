//! Typed names written into result files. Each enum's `Display`, `FromStr` and serde forms are
//! the same snake_case word, so a name printed, parsed or stored is always one of the variants.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// A name that is not one of an enum's variants.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownName {
    /// What was being parsed ("outcome", "arm simulation").
    pub what: &'static str,
    /// The text given.
    pub given: String,
    /// Every accepted name.
    pub known: Vec<&'static str>,
}

impl fmt::Display for UnknownName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown {} `{}` (known: {})",
            self.what,
            self.given,
            self.known.join(", ")
        )
    }
}

impl std::error::Error for UnknownName {}

/// Implements `ALL`, `as_str`, `Display` and `FromStr` from one list of (variant, name) pairs.
macro_rules! named_enum {
    ($ty:ident, $what:literal, [$(($variant:ident, $name:literal)),+ $(,)?]) => {
        impl $ty {
            /// Every variant, in table order.
            pub const ALL: &'static [$ty] = &[$($ty::$variant),+];

            /// The snake_case name (as in result files and on the command line).
            pub fn as_str(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
        }

        impl fmt::Display for $ty {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.as_str())
            }
        }

        impl FromStr for $ty {
            type Err = UnknownName;

            fn from_str(s: &str) -> Result<Self, Self::Err> {
                $ty::ALL
                    .iter()
                    .copied()
                    .find(|v| v.as_str() == s)
                    .ok_or_else(|| UnknownName {
                        what: $what,
                        given: s.to_string(),
                        known: $ty::ALL.iter().map(|v| v.as_str()).collect(),
                    })
            }
        }
    };
}

/// How an episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Lifted and held.
    Success,
    /// The gripper closed without both pads ever touching the object.
    MissedGrasp,
    /// The object was held and lifted, then slipped or dropped.
    SlipOrDrop,
    /// Arm or gripper hit the table or itself.
    Collision,
    /// No in-limit inverse-kinematics solution for a grasp pose.
    IkFailure,
    /// The object was pushed off the table.
    ObjectOffTable,
    /// A robot part pushed on the object or the table harder than the protective stop
    /// threshold (`task.protective_stop_force`): the robot stopped, as a cobot's collision
    /// detection stops it.
    ProtectiveStop,
    /// The time limit passed without any of the above.
    Timeout,
    /// The physics state became non-finite.
    PhysicsFault,
}

named_enum!(
    Outcome,
    "outcome",
    [
        (Success, "success"),
        (MissedGrasp, "missed_grasp"),
        (SlipOrDrop, "slip_or_drop"),
        (Collision, "collision"),
        (IkFailure, "ik_failure"),
        (ObjectOffTable, "object_off_table"),
        (ProtectiveStop, "protective_stop"),
        (Timeout, "timeout"),
        (PhysicsFault, "physics_fault"),
    ]
);

/// How the arm is simulated (the environment's `arm.model` setting, the CLI's `--arm`, Python's
/// `arm=`): the one enum for it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum ArmSimulation {
    /// Kinematic links placed by FK (fast; the default): joint angles integrate the commanded
    /// velocities.
    #[default]
    Servo,
    /// A rapier multibody with joint velocity motors and the arm's mass properties.
    Multibody,
}

named_enum!(
    ArmSimulation,
    "arm simulation",
    [(Servo, "servo"), (Multibody, "multibody")]
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_from_str_and_serde_agree_on_every_name() {
        for &o in Outcome::ALL {
            let json = serde_json::to_string(&o).unwrap();
            assert_eq!(json, format!("\"{o}\""));
            assert_eq!(o.to_string().parse::<Outcome>(), Ok(o));
        }
        for &a in ArmSimulation::ALL {
            assert_eq!(serde_json::to_string(&a).unwrap(), format!("\"{a}\""));
            assert_eq!(a.to_string().parse::<ArmSimulation>(), Ok(a));
        }
        assert_eq!(Outcome::ALL.len(), 9);
    }

    #[test]
    fn an_unknown_name_is_refused_with_the_choices() {
        let e = "teleported".parse::<Outcome>().unwrap_err();
        let text = e.to_string();
        assert!(text.contains("`teleported`"), "{text}");
        assert!(text.contains("missed_grasp, slip_or_drop"), "{text}");
        assert!(
            "Servo".parse::<ArmSimulation>().is_err(),
            "names are case-sensitive"
        );
    }
}
