//! The geometric Jacobian of any serial chain read from a URDF, for N movable joints.

use nalgebra::{DMatrix, Isometry3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::pose::Pose;
use crate::urdf::JointKind;
use crate::urdf::SerialChain;

impl SerialChain {
    /// The tip's pose in the root frame and the geometric Jacobian (6 × N, rows: linear
    /// velocity [m/s] then angular velocity [rad/s] of the tip, in the root frame; columns: the
    /// movable joints in order, per rad/s or m/s) at joint values `q`. Panics if
    /// `q.len() != dof()`.
    pub fn fk_jacobian(&self, q: &[f64]) -> (Pose, DMatrix<f64>) {
        assert_eq!(
            q.len(),
            self.dof(),
            "SerialChain::fk_jacobian: wrong number of values"
        );
        let mut t = Isometry3::identity();
        let mut values = q.iter();
        // Each movable joint's axis and origin in the root frame, and whether it slides.
        let mut axes: Vec<(Vector3<f64>, Vector3<f64>, bool)> = Vec::with_capacity(q.len());
        for joint in &self.joints {
            t *= joint.origin.iso;
            let axis = Unit::new_unchecked(Vector3::from(joint.axis));
            let world_axis = t.rotation * axis.into_inner();
            match joint.kind {
                JointKind::Revolute | JointKind::Continuous => {
                    axes.push((world_axis, t.translation.vector, false));
                    let angle = *values.next().expect("counted by dof");
                    t *= UnitQuaternion::from_axis_angle(&axis, angle);
                }
                JointKind::Prismatic => {
                    axes.push((world_axis, t.translation.vector, true));
                    let offset = *values.next().expect("counted by dof");
                    t *= Translation3::from(axis.into_inner() * offset);
                }
                _ => {}
            }
        }
        let tip = t.translation.vector;
        let mut jacobian = DMatrix::zeros(6, q.len());
        for (c, (z, origin, slides)) in axes.iter().enumerate() {
            let (linear, angular) = if *slides {
                (*z, Vector3::zeros())
            } else {
                (z.cross(&(tip - origin)), *z)
            };
            for r in 0..3 {
                jacobian[(r, c)] = linear[r];
                jacobian[(r + 3, c)] = angular[r];
            }
        }
        (Pose { iso: t }, jacobian)
    }
}
