//! A task-space correction of the scripted grasp: an offset of the TCP [m] and of its yaw about
//! the table's vertical [rad], both in the table frame, that the script's joint reference follows.
//!
//! The offset is carried into joint space through the arm's Jacobian at the reference joints
//! (damped least squares, `Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ [R·Δp; R·ẑ·Δψ]`, `R` the table frame's rotation
//! in `base_link`): kinematics first. For the few centimetres a correction spans, the first-order
//! map is accurate to well under a millimetre at the TCP (a test checks it).

use fairgrasp_kinematics::{ArmModel, EndFrame, Pose};
use nalgebra::{Matrix6, Vector3, Vector6};
use serde::Serialize;

/// Damping λ of the least-squares map (mixed units: m and rad); as the env's TCP action.
pub const DAMPING: f64 = 0.01;

/// An offset of the grasp, table frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TaskCorrection {
    /// TCP offset along the table frame's x, y, z [m].
    pub offset: [f64; 3],
    /// Yaw offset about the table's vertical [rad].
    pub yaw: f64,
}

impl TaskCorrection {
    /// No correction.
    pub const ZERO: TaskCorrection = TaskCorrection {
        offset: [0.0; 3],
        yaw: 0.0,
    };

    /// Whether this is exactly no correction.
    pub fn is_zero(&self) -> bool {
        *self == Self::ZERO
    }
}

/// How far and how fast a learned correction may go.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CorrectionLimits {
    /// Largest offset along each table axis [m] (5 cm: above the families' 1.5–3 cm errors).
    pub max_offset: f64,
    /// Largest yaw offset [rad] (15°: the miscalibrated cells are off by 2–2.5°).
    pub max_yaw: f64,
    /// Offset rate per unit of action [m/s].
    pub speed: f64,
    /// Yaw-offset rate per unit of action [rad/s].
    pub yaw_rate: f64,
}

impl Default for CorrectionLimits {
    fn default() -> Self {
        Self {
            max_offset: 0.05,
            max_yaw: 15f64.to_radians(),
            speed: 0.1,
            yaw_rate: 0.5,
        }
    }
}

impl CorrectionLimits {
    /// `c` moved by the rates `action[0..4]` (each clipped to [-1, 1]) over `dt` [s], then
    /// clamped to the limits.
    pub fn integrate(&self, c: &TaskCorrection, action: &[f64], dt: f64) -> TaskCorrection {
        let a = |i: usize| action.get(i).copied().unwrap_or(0.0).clamp(-1.0, 1.0);
        let m = self.max_offset;
        TaskCorrection {
            offset: [0, 1, 2].map(|i| (c.offset[i] + a(i) * self.speed * dt).clamp(-m, m)),
            yaw: (c.yaw + a(3) * self.yaw_rate * dt).clamp(-self.max_yaw, self.max_yaw),
        }
    }

    /// The correction scaled into [-1, 1] per entry (what the policy sees of it).
    pub fn normalized(&self, c: &TaskCorrection) -> [f64; 4] {
        [
            c.offset[0] / self.max_offset,
            c.offset[1] / self.max_offset,
            c.offset[2] / self.max_offset,
            c.yaw / self.max_yaw,
        ]
    }
}

/// The joint offset [rad] at joints `q` that moves the TCP by `c` (first order).
/// `table_in_base` is the table frame in `base_link`.
pub fn joint_offset(
    model: &ArmModel,
    table_in_base: &Pose,
    q: &[f64; 6],
    c: &TaskCorrection,
) -> [f64; 6] {
    if c.is_zero() {
        return [0.0; 6];
    }
    let to_base = table_in_base.iso.rotation;
    let linear = to_base * Vector3::from(c.offset);
    let angular = to_base * Vector3::z() * c.yaw;
    let twist = Vector6::new(
        linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
    );
    let j = model.jacobian(q, EndFrame::Tcp);
    let damped = j * j.transpose() + Matrix6::identity() * DAMPING * DAMPING;
    let Some(solve) = damped.cholesky() else {
        return [0.0; 6];
    };
    let dq = j.transpose() * solve.solve(&twist);
    std::array::from_fn(|i| dq[i])
}

/// `q + joint_offset(q, c)`.
pub fn corrected(
    model: &ArmModel,
    table_in_base: &Pose,
    q: &[f64; 6],
    c: &TaskCorrection,
) -> [f64; 6] {
    let dq = joint_offset(model, table_in_base, q, c);
    std::array::from_fn(|i| q[i] + dq[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use fairgrasp_kinematics::ArmKind;

    const HOME: [f64; 6] = fairgrasp_env::HOME_JOINTS;

    #[test]
    fn a_few_centimetres_of_offset_move_the_tcp_by_that_much_to_the_millimetre() {
        let model = ArmKind::Fr3.model();
        let tilted = Pose {
            iso: nalgebra::Isometry3::rotation(Vector3::new(0.08, -0.05, 0.0)),
        };
        for table in [Pose::identity(), tilted] {
            let c = TaskCorrection {
                offset: [0.03, -0.02, 0.01],
                yaw: 0.05,
            };
            let before = model.fk_tcp(&HOME);
            let after = model.fk_tcp(&corrected(&model, &table, &HOME, &c));
            let moved = after.iso.translation.vector - before.iso.translation.vector;
            let want = table.iso.rotation * Vector3::from(c.offset);
            assert!((moved - want).norm() < 1e-3, "{moved:?} vs {want:?}");
            let turn = (before.iso.rotation.inverse() * after.iso.rotation).scaled_axis();
            let turn_in_base = before.iso.rotation * turn;
            let up = table.iso.rotation * Vector3::z();
            assert!(
                (turn_in_base.dot(&up) - c.yaw).abs() < 2e-3,
                "{turn_in_base:?}"
            );
            assert!(
                (turn_in_base - up * c.yaw).norm() < 3e-3,
                "tilted: {turn_in_base:?}"
            );
        }
    }

    #[test]
    fn integration_follows_the_rates_and_stops_at_the_limits() {
        let limits = CorrectionLimits::default();
        let mut c = TaskCorrection::ZERO;
        c = limits.integrate(&c, &[1.0, -0.5, 0.0, 0.2], 0.1);
        assert!((c.offset[0] - 0.01).abs() < 1e-12 && (c.offset[1] + 0.005).abs() < 1e-12);
        assert!((c.yaw - 0.01).abs() < 1e-12);
        for _ in 0..1000 {
            c = limits.integrate(&c, &[5.0, -5.0, 1.0, -1.0], 0.1);
        }
        assert_eq!(c.offset, [0.05, -0.05, 0.05]);
        assert_eq!(c.yaw, -limits.max_yaw);
        assert_eq!(limits.normalized(&c), [1.0, -1.0, 1.0, -1.0]);
    }
}
