//! One URDF joint as fairgrasp keeps it: its kind, links, origin, axis and limits.

use serde::Serialize;

use crate::pose::Pose;

/// A URDF joint type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
    Spherical,
}

impl JointKind {
    /// Every joint type URDF defines.
    pub const ALL: [JointKind; 7] = [
        JointKind::Revolute,
        JointKind::Continuous,
        JointKind::Prismatic,
        JointKind::Fixed,
        JointKind::Floating,
        JointKind::Planar,
        JointKind::Spherical,
    ];

    /// The joint type of a URDF `type` attribute (`None` for anything else).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The URDF spelling.
    pub fn name(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Continuous => "continuous",
            JointKind::Prismatic => "prismatic",
            JointKind::Fixed => "fixed",
            JointKind::Floating => "floating",
            JointKind::Planar => "planar",
            JointKind::Spherical => "spherical",
        }
    }

    /// Does URDF require this joint to have a `<limit>` (and do its limits bound its position)?
    pub fn has_position_limits(self) -> bool {
        matches!(self, JointKind::Revolute | JointKind::Prismatic)
    }

    /// Does this joint add one degree of freedom along an axis?
    pub fn is_single_axis(self) -> bool {
        matches!(
            self,
            JointKind::Revolute | JointKind::Continuous | JointKind::Prismatic
        )
    }
}

/// One joint as the URDF states it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct UrdfJoint {
    pub name: String,
    pub kind: JointKind,
    pub parent: String,
    pub child: String,
    /// `T_parent_joint` at zero joint value \[m, rad\].
    #[serde(skip)]
    pub origin: Pose,
    /// Unit axis in the joint frame.
    pub axis: [f64; 3],
    /// Position limits \[rad or m\]; `None` for continuous and fixed joints.
    pub limits: Option<[f64; 2]>,
    /// Velocity limit \[rad/s or m/s\] (0 where the URDF gives none).
    pub max_velocity: f64,
    /// Effort limit \[N·m or N\] (0 where the URDF gives none).
    pub max_effort: f64,
}
