//! urdf-rs's robot mapped into fairgrasp's model: the one place that reads a `urdf_rs::Robot`.
//!
//! From each joint fairgrasp keeps its type, links, origin, unit axis, position limits (revolute
//! and prismatic only), velocity and effort limits; from the robot its name and link names.
//! urdf-rs has already applied URDF's defaults (no `<origin>` is the identity, no `<axis>` is
//! `1 0 0`, a `<limit>` without `lower`, `upper` or `effort` has 0 there) and turned a URDF 1.1
//! `quat_xyzw` into `rpy`.

use nalgebra::Vector3;

use crate::pose::Pose;
use crate::urdf::error::UrdfError;
use crate::urdf::joint::{JointKind, UrdfJoint};

/// The robot's name, its link names in file order and its joints in file order.
pub(crate) struct Mapped {
    pub name: String,
    pub links: Vec<String>,
    pub joints: Vec<UrdfJoint>,
}

/// Maps `robot` (read from `file`, which messages name), refusing a non-finite number, a zero
/// axis on a moving joint and inverted limits.
pub(crate) fn map_robot(file: &str, robot: &urdf_rs::Robot) -> Result<Mapped, UrdfError> {
    let joints = robot
        .joints
        .iter()
        .map(|j| map_joint(file, j))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Mapped {
        name: robot.name.clone(),
        links: robot.links.iter().map(|l| l.name.clone()).collect(),
        joints,
    })
}

fn kind_of(joint_type: &urdf_rs::JointType) -> JointKind {
    match joint_type {
        urdf_rs::JointType::Revolute => JointKind::Revolute,
        urdf_rs::JointType::Continuous => JointKind::Continuous,
        urdf_rs::JointType::Prismatic => JointKind::Prismatic,
        urdf_rs::JointType::Fixed => JointKind::Fixed,
        urdf_rs::JointType::Floating => JointKind::Floating,
        urdf_rs::JointType::Planar => JointKind::Planar,
        urdf_rs::JointType::Spherical => JointKind::Spherical,
    }
}

fn map_joint(file: &str, j: &urdf_rs::Joint) -> Result<UrdfJoint, UrdfError> {
    let bad = |problem: String| UrdfError::BadJoint {
        file: file.to_string(),
        joint: j.name.clone(),
        problem,
    };
    let limit = &j.limit;
    // Text passed the pre-check, which refuses these with their line; a `urdf_rs::Robot` built
    // in code did not.
    let numbers = [
        ("<origin> xyz", &j.origin.xyz.0[..]),
        ("<origin> rpy", &j.origin.rpy.0[..]),
        ("<axis> xyz", &j.axis.xyz.0[..]),
        (
            "<limit>",
            &[limit.lower, limit.upper, limit.velocity, limit.effort][..],
        ),
    ];
    if let Some((what, values)) = numbers
        .iter()
        .find(|(_, v)| v.iter().any(|x| !x.is_finite()))
    {
        return Err(bad(format!("{what} holds a non-finite number: {values:?}")));
    }
    let kind = kind_of(&j.joint_type);
    let axis = unit_axis(j.axis.xyz.0);
    if kind.is_single_axis() && axis.is_none() {
        let [x, y, z] = j.axis.xyz.0;
        return Err(bad(format!(
            "its axis is zero: <axis xyz=\"{x} {y} {z}\"/>; a unit vector is expected"
        )));
    }
    let limits = if kind.has_position_limits() {
        let (lower, upper) = (limit.lower, limit.upper);
        if lower > upper {
            return Err(bad(format!(
                "limit lower = {lower} is above upper = {upper}"
            )));
        }
        Some([lower, upper])
    } else {
        None
    };
    Ok(UrdfJoint {
        name: j.name.clone(),
        kind,
        parent: j.parent.link.clone(),
        child: j.child.link.clone(),
        origin: Pose::from_xyz_rpy(j.origin.xyz.0, j.origin.rpy.0),
        axis: axis.unwrap_or([0.0, 0.0, 1.0]),
        limits,
        max_velocity: limit.velocity,
        max_effort: limit.effort,
    })
}

/// `axis` scaled to length 1 (`None` when it is zero). Scaled by its largest component first, so
/// that 1e200 does not overflow the norm.
fn unit_axis(axis: [f64; 3]) -> Option<[f64; 3]> {
    let axis = Vector3::from(axis);
    let largest = axis.amax();
    if largest < 1e-9 {
        return None;
    }
    let axis = axis / largest;
    Some((axis / axis.norm()).into())
}
