//! A serial chain: the joints from the root link to a tip link, with forward kinematics.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::pose::Pose;
use crate::urdf::joint::{JointKind, UrdfJoint};

/// The joints from the root link to a tip link, with forward kinematics.
#[derive(Clone, Debug, PartialEq)]
pub struct SerialChain {
    /// Joints root → tip, fixed ones included.
    pub joints: Vec<UrdfJoint>,
    /// The tip link.
    pub tip: String,
}

impl SerialChain {
    /// Number of movable joints (the length FK expects).
    pub fn dof(&self) -> usize {
        self.joints
            .iter()
            .filter(|j| j.kind.is_single_axis())
            .count()
    }

    /// Names of the movable joints, in order.
    pub fn joint_names(&self) -> Vec<&str> {
        self.joints
            .iter()
            .filter(|j| j.kind.is_single_axis())
            .map(|j| j.name.as_str())
            .collect()
    }

    /// `T_root_tip` for movable-joint values `q` \[rad or m\]. Panics if `q.len() != dof()`.
    pub fn fk(&self, q: &[f64]) -> Pose {
        self.walk(q, |_, _, _| {})
    }

    /// Walks the chain at joint values `q`, calling `at_joint(frame, axis, slides)` for each
    /// movable joint with its frame in the root before its motion, its axis in the root frame and
    /// whether it is prismatic; returns `T_root_tip`. Panics if `q.len() != dof()`.
    pub(crate) fn walk(
        &self,
        q: &[f64],
        mut at_joint: impl FnMut(&Isometry3<f64>, Vector3<f64>, bool),
    ) -> Pose {
        assert_eq!(
            q.len(),
            self.dof(),
            "SerialChain: wrong number of joint values"
        );
        let mut t = Isometry3::identity();
        let mut values = q.iter();
        for joint in &self.joints {
            t *= joint.origin.iso;
            let axis = Unit::new_unchecked(Vector3::from(joint.axis));
            match joint.kind {
                JointKind::Revolute | JointKind::Continuous => {
                    at_joint(&t, t.rotation * axis.into_inner(), false);
                    let angle = *values.next().expect("counted by dof");
                    t *= UnitQuaternion::from_axis_angle(&axis, angle);
                }
                JointKind::Prismatic => {
                    at_joint(&t, t.rotation * axis.into_inner(), true);
                    let offset = *values.next().expect("counted by dof");
                    t *= Translation3::from(axis.into_inner() * offset);
                }
                _ => {}
            }
        }
        Pose { iso: t }
    }
}
