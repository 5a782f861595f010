//! Rigid poses and the frame algebra the rest of fairgrasp is built on.
//!
//! A [`Pose`] is a rigid transform `T_a_b`: it maps coordinates expressed in frame `b` into frame
//! `a` (`p_a = T_a_b · p_b`). Translations are in metres, angles in radians.
//!
//! Conventions, written down once:
//! - **roll, pitch, yaw** are the URDF / ROS convention: rotations about the *fixed* x, y and z
//!   axes, applied in that order, so `R = Rz(yaw) · Ry(pitch) · Rx(roll)`. Pitch is returned in
//!   [−π/2, π/2].
//! - **quaternions** are written `[x, y, z, w]` (scalar last), as PyBullet and ROS write them.
//!
//! The two operations of PyBullet's frame recipe map as follows:
//! `invertTransform(T)` is [`Pose::inverse`], `multiplyTransforms(A, B)` is [`Pose::compose`].

use nalgebra::{Isometry3, Point3, Quaternion, Translation3, UnitQuaternion, Vector3};
use serde::Serialize;

/// A rigid transform `T_a_b` (metres, radians), a thin wrapper over nalgebra's `Isometry3<f64>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The underlying isometry: rotation then translation, `p_a = R · p_b + t`.
    pub iso: Isometry3<f64>,
}

/// Why a pose could not be built from raw numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PoseError {
    /// A component is NaN or infinite.
    #[error("{field} has a non-finite component: {values:?}")]
    NonFinite {
        /// Which input: "xyz", "rpy" or "quat_xyzw".
        field: &'static str,
        /// The values as given.
        values: Vec<f64>,
    },
    /// A quaternion whose norm is too far from 1 to be a typo-free rotation.
    #[error(
        "quat_xyzw {values:?} has norm {norm:.6}; a rotation quaternion must have norm 1 (±1e-3)"
    )]
    NotUnitQuaternion {
        /// The values as given.
        values: [f64; 4],
        /// Their Euclidean norm.
        norm: f64,
    },
}

/// Plain-number view of a pose, for JSON output and tables.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PoseRecord {
    /// Position \[m\].
    pub xyz: [f64; 3],
    /// Orientation as a unit quaternion `[x, y, z, w]`.
    pub quat_xyzw: [f64; 4],
    /// Orientation as URDF roll, pitch, yaw \[rad\].
    pub rpy: [f64; 3],
}

impl Default for Pose {
    fn default() -> Self {
        Self::identity()
    }
}

impl From<Isometry3<f64>> for Pose {
    fn from(iso: Isometry3<f64>) -> Self {
        Self { iso }
    }
}

impl From<Pose> for Isometry3<f64> {
    fn from(pose: Pose) -> Self {
        pose.iso
    }
}

fn check_finite(field: &'static str, values: &[f64]) -> Result<(), PoseError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(PoseError::NonFinite {
            field,
            values: values.to_vec(),
        })
    }
}

impl Pose {
    /// The identity transform.
    pub fn identity() -> Self {
        Self {
            iso: Isometry3::identity(),
        }
    }

    /// A pure translation \[m\].
    pub fn from_xyz(xyz: [f64; 3]) -> Self {
        Self {
            iso: Isometry3::translation(xyz[0], xyz[1], xyz[2]),
        }
    }

    /// From a position \[m\] and URDF roll, pitch, yaw \[rad\] (`R = Rz(yaw)·Ry(pitch)·Rx(roll)`).
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        let rotation = UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]);
        Self {
            iso: Isometry3::from_parts(Translation3::new(xyz[0], xyz[1], xyz[2]), rotation),
        }
    }

    /// Like [`Pose::from_xyz_rpy`], refusing NaN and infinite inputs.
    pub fn try_from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Result<Self, PoseError> {
        check_finite("xyz", &xyz)?;
        check_finite("rpy", &rpy)?;
        Ok(Self::from_xyz_rpy(xyz, rpy))
    }

    /// From a position \[m\] and a quaternion `[x, y, z, w]`; the quaternion is renormalised if its
    /// norm is within 1e-3 of 1 and refused otherwise.
    pub fn try_from_xyz_quat_xyzw(xyz: [f64; 3], quat_xyzw: [f64; 4]) -> Result<Self, PoseError> {
        check_finite("xyz", &xyz)?;
        check_finite("quat_xyzw", &quat_xyzw)?;
        let [x, y, z, w] = quat_xyzw;
        let q = Quaternion::new(w, x, y, z);
        let norm = q.norm();
        if (norm - 1.0).abs() > 1e-3 {
            return Err(PoseError::NotUnitQuaternion {
                values: quat_xyzw,
                norm,
            });
        }
        Ok(Self {
            iso: Isometry3::from_parts(
                Translation3::new(xyz[0], xyz[1], xyz[2]),
                UnitQuaternion::from_quaternion(q),
            ),
        })
    }

    /// Position \[m\].
    pub fn xyz(&self) -> [f64; 3] {
        let t = self.iso.translation.vector;
        [t.x, t.y, t.z]
    }

    /// URDF roll, pitch, yaw \[rad\]; pitch in [−π/2, π/2].
    pub fn rpy(&self) -> [f64; 3] {
        let (r, p, y) = self.iso.rotation.euler_angles();
        [r, p, y]
    }

    /// Unit quaternion `[x, y, z, w]`, with `w ≥ 0` so that equal rotations print equally.
    pub fn quat_xyzw(&self) -> [f64; 4] {
        let c = self.iso.rotation.coords; // stored as [i, j, k, w]
        let sign = if c.w < 0.0 { -1.0 } else { 1.0 };
        [sign * c.x, sign * c.y, sign * c.z, sign * c.w]
    }

    /// Rotation matrix, row-major.
    pub fn rotation_rows(&self) -> [[f64; 3]; 3] {
        let m = self.iso.rotation.to_rotation_matrix().into_inner();
        [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ]
    }

    /// All three views at once, for printing.
    pub fn record(&self) -> PoseRecord {
        PoseRecord {
            xyz: self.xyz(),
            quat_xyzw: self.quat_xyzw(),
            rpy: self.rpy(),
        }
    }

    /// `T_a_c = T_a_b · T_b_c` (PyBullet's `multiplyTransforms`).
    pub fn compose(&self, b_to_c: &Pose) -> Pose {
        Pose {
            iso: self.iso * b_to_c.iso,
        }
    }

    /// `T_b_a = T_a_b⁻¹` (PyBullet's `invertTransform`).
    pub fn inverse(&self) -> Pose {
        Pose {
            iso: self.iso.inverse(),
        }
    }

    /// A point given in frame `b`, expressed in frame `a`: `p_a = T_a_b · p_b`.
    pub fn transform_point(&self, p_b: [f64; 3]) -> [f64; 3] {
        let p = self
            .iso
            .transform_point(&Point3::new(p_b[0], p_b[1], p_b[2]));
        [p.x, p.y, p.z]
    }

    /// A free vector (direction, velocity) in frame `b`, expressed in frame `a`: rotation only.
    pub fn transform_vector(&self, v_b: [f64; 3]) -> [f64; 3] {
        let v = self.iso.rotation * Vector3::new(v_b[0], v_b[1], v_b[2]);
        [v.x, v.y, v.z]
    }

    /// Distance between the two origins \[m\] and the angle of the relative rotation \[rad\].
    pub fn distance_to(&self, other: &Pose) -> (f64, f64) {
        let dp = (self.iso.translation.vector - other.iso.translation.vector).norm();
        let dr = self.iso.rotation.angle_to(&other.iso.rotation);
        (dp, dr)
    }
}

/// A point given in `world`, expressed in the arm's `base_link` frame, for an arm whose base
/// sits at `base_in_world` (`T_world_base`): `p_base = T_world_base⁻¹ · p_world`.
///
/// This is the seed recipe's `invertTransform` + `multiplyTransforms`. Subtracting the base
/// position (`p_world − t_world_base`) is only right when the base is not rotated; see
/// [`naive_world_to_base`].
pub fn world_to_base(base_in_world: &Pose, p_world: [f64; 3]) -> [f64; 3] {
    base_in_world.inverse().transform_point(p_world)
}

/// A point given in the arm's `base_link` frame, expressed in `world`: `p_world = T_world_base · p_base`.
pub fn base_to_world(base_in_world: &Pose, p_base: [f64; 3]) -> [f64; 3] {
    base_in_world.transform_point(p_base)
}

/// A pose given in `world`, expressed in `base_link`: `T_base_x = T_world_base⁻¹ · T_world_x`.
pub fn world_pose_to_base(base_in_world: &Pose, pose_in_world: &Pose) -> Pose {
    base_in_world.inverse().compose(pose_in_world)
}

/// A pose given in `base_link`, expressed in `world`: `T_world_x = T_world_base · T_base_x`.
pub fn base_pose_to_world(base_in_world: &Pose, pose_in_base: &Pose) -> Pose {
    base_in_world.compose(pose_in_base)
}

/// The common mistake, kept to demonstrate it: `p_world − t_world_base`, which ignores the
/// base's rotation. It equals [`world_to_base`] only when the base is not rotated.
pub fn naive_world_to_base(base_in_world: &Pose, p_world: [f64; 3]) -> [f64; 3] {
    let t = base_in_world.xyz();
    [p_world[0] - t[0], p_world[1] - t[1], p_world[2] - t[2]]
}
