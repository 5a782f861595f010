//! The geometric Jacobian of any serial chain read from a URDF, for N movable joints.

use nalgebra::{DMatrix, Vector3};

use crate::pose::Pose;
use crate::urdf::SerialChain;

impl SerialChain {
    /// The tip's pose in the root frame and the geometric Jacobian (6 × N, rows: linear
    /// velocity \[m/s\] then angular velocity \[rad/s\] of the tip, in the root frame; columns: the
    /// movable joints in order, per rad/s or m/s) at joint values `q`. Panics if
    /// `q.len() != dof()`.
    pub fn fk_jacobian(&self, q: &[f64]) -> (Pose, DMatrix<f64>) {
        // Each movable joint's axis and origin in the root frame, and whether it slides.
        let mut axes: Vec<(Vector3<f64>, Vector3<f64>, bool)> = Vec::with_capacity(q.len());
        let pose = self.walk(q, |frame, axis, slides| {
            axes.push((axis, frame.translation.vector, slides));
        });
        let tip = pose.iso.translation.vector;
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
        (pose, jacobian)
    }
}
