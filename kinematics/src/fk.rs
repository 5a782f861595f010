//! Closed-form forward kinematics and the geometric Jacobian from the DH table.
//!
//! All poses are in `base_link`; joint angles in radians, lengths in metres.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

use nalgebra::{Isometry3, Matrix6, Translation3, UnitQuaternion, Vector3};

use crate::model::{ArmModel, DhRow};
use crate::pose::Pose;

/// The frame whose pose or Jacobian is asked for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum EndFrame {
    /// `tool0`, the flange (DH frame 6).
    #[default]
    Flange,
    /// `tcp`, the gripper's tool centre point between the pads.
    Tcp,
}

impl EndFrame {
    /// The URDF frame name.
    pub fn name(self) -> &'static str {
        match self {
            EndFrame::Flange => "tool0",
            EndFrame::Tcp => "tcp",
        }
    }
}

/// `T_{i-1}_i = Rz(θ)·Tz(d)·Tx(a)·Rx(α)` as an isometry.
pub fn dh_transform(row: &DhRow, theta: f64) -> Isometry3<f64> {
    // Rz(θ)·Rx(α) as a quaternion product: (cos θ/2, 0, 0, sin θ/2)·(cos α/2, sin α/2, 0, 0).
    // One sin_cos per joint: sin θ and cos θ follow from the half angle.
    let (sh, ch) = (0.5 * theta).sin_cos();
    let (st, ct) = (2.0 * sh * ch, ch * ch - sh * sh);
    let (sa, ca) = half_angle_sin_cos(row.alpha);
    let q = nalgebra::Quaternion::new(ch * ca, ch * sa, sh * sa, sh * ca);
    Isometry3::from_parts(
        Translation3::new(row.a * ct, row.a * st, row.d),
        UnitQuaternion::new_unchecked(q),
    )
}

/// `(sin α/2, cos α/2)`, exact and free for the twists of UR-like arms (0, ±π/2).
fn half_angle_sin_cos(alpha: f64) -> (f64, f64) {
    if alpha == 0.0 {
        (0.0, 1.0)
    } else if alpha == FRAC_PI_2 {
        (FRAC_1_SQRT_2, FRAC_1_SQRT_2)
    } else if alpha == -FRAC_PI_2 {
        (-FRAC_1_SQRT_2, FRAC_1_SQRT_2)
    } else {
        (0.5 * alpha).sin_cos()
    }
}

impl ArmModel {
    /// Poses of DH frames 1 … 6 in `base_link` (frame 6 is `tool0`).
    pub fn fk_frames(&self, q: &[f64; 6]) -> [Isometry3<f64>; 6] {
        let mut frames = [Isometry3::identity(); 6];
        let mut t = Isometry3::identity();
        for i in 0..6 {
            t *= dh_transform(&self.dh[i], q[i]);
            frames[i] = t;
        }
        frames
    }

    /// Poses of the seven URDF link frames (`base_link` … `wrist3_link`) in `base_link`.
    ///
    /// URDF link i (i ≥ 1) is DH frame i−1 turned by θ_i about its z axis; the collision capsules
    /// and mass properties of [`ArmModel`] are given in these frames.
    pub fn link_poses(&self, q: &[f64; 6]) -> [Isometry3<f64>; 7] {
        self.link_poses_and_flange(q).0
    }

    /// [`ArmModel::link_poses`] and [`ArmModel::fk_flange`] from one pass down the chain, each
    /// bit for bit what its own function returns (the flange is the same product of the same
    /// DH transforms): for callers that place the links and the gripper at one `q` \[rad\].
    pub fn link_poses_and_flange(&self, q: &[f64; 6]) -> ([Isometry3<f64>; 7], Pose) {
        let mut poses = [Isometry3::identity(); 7];
        let mut dh_frame = Isometry3::identity();
        for i in 0..6 {
            poses[i + 1] = dh_frame * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), q[i]);
            dh_frame *= dh_transform(&self.dh[i], q[i]);
        }
        (poses, Pose { iso: dh_frame })
    }

    /// `T_base_tool0`: the flange pose.
    pub fn fk_flange(&self, q: &[f64; 6]) -> Pose {
        let mut t = Isometry3::identity();
        for (row, &theta) in self.dh.iter().zip(q) {
            t *= dh_transform(row, theta);
        }
        Pose { iso: t }
    }

    /// `T_base_tcp`: the tool centre point between the finger pads.
    pub fn fk_tcp(&self, q: &[f64; 6]) -> Pose {
        self.fk_flange(q).compose(&self.tcp_in_flange)
    }

    /// Pose of `frame` in `base_link`.
    pub fn fk(&self, q: &[f64; 6], frame: EndFrame) -> Pose {
        match frame {
            EndFrame::Flange => self.fk_flange(q),
            EndFrame::Tcp => self.fk_tcp(q),
        }
    }

    /// Geometric Jacobian of `frame` in `base_link`: rows 0–2 map joint rates \[rad/s\] to the
    /// frame origin's linear velocity \[m/s\], rows 3–5 to its angular velocity \[rad/s\].
    ///
    /// Column i is `[z_{i-1} × (p − o_{i-1}); z_{i-1}]`, with joint i turning about DH axis z_{i-1}.
    pub fn jacobian(&self, q: &[f64; 6], frame: EndFrame) -> Matrix6<f64> {
        let frames = self.fk_frames(q);
        let end = match frame {
            EndFrame::Flange => frames[5],
            EndFrame::Tcp => frames[5] * self.tcp_in_flange.iso,
        };
        let p = end.translation.vector;
        let mut j = Matrix6::zeros();
        for i in 0..6 {
            let (z, o) = if i == 0 {
                (Vector3::z(), Vector3::zeros())
            } else {
                (
                    frames[i - 1].rotation * Vector3::z(),
                    frames[i - 1].translation.vector,
                )
            };
            let linear = z.cross(&(p - o));
            j.fixed_view_mut::<3, 1>(0, i).copy_from(&linear);
            j.fixed_view_mut::<3, 1>(3, i).copy_from(&z);
        }
        j
    }
}

/// The damped least-squares solution of `J Δq = e`: `Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e` (λ = `damping`,
/// mixed units m and rad). Near a singularity it trades accuracy for a bounded `Δq`. None if the
/// damped matrix is not positive definite (only for a non-finite `J` or `λ = 0` at a singularity).
pub fn damped_least_squares(
    jacobian: &Matrix6<f64>,
    error: &nalgebra::Vector6<f64>,
    damping: f64,
) -> Option<nalgebra::Vector6<f64>> {
    let damped = jacobian * jacobian.transpose() + Matrix6::identity() * damping * damping;
    let solve = damped.cholesky()?;
    Some(jacobian.transpose() * solve.solve(error))
}

/// Yoshikawa's manipulability `sqrt(det(J·Jᵀ))` (mixed units: it is a product of singular
/// values; compare values only for the same frame and arm). Zero at a singularity.
pub fn manipulability(jacobian: &Matrix6<f64>) -> f64 {
    (jacobian * jacobian.transpose())
        .determinant()
        .max(0.0)
        .sqrt()
}

/// The smallest singular value of the Jacobian: the speed of the slowest Cartesian direction per
/// unit joint rate. Zero at a singularity; the usual "distance to singularity" measure.
pub fn min_singular_value(jacobian: &Matrix6<f64>) -> f64 {
    jacobian
        .singular_values()
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
}
