//! A task-space correction of the scripted grasp: an offset of the TCP \[m\] and of its yaw about
//! the table's vertical \[rad\], both in the table frame, that the script's joint reference
//! follows.
//!
//! The offset is carried into joint space through the arm's Jacobian at the reference joints:
//! a few damped least-squares Newton steps, `Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e`, toward the TCP pose
//! moved by `R·Δp` and turned by `Δψ` about the table's vertical `R·ẑ` (`R` the table frame's
//! rotation in `base_link`): kinematics first. (One step alone, the first-order map, is off by
//! ~3 mm for a 3.7 cm offset; three are exact to micrometres.)

use fairgrasp_kinematics::{ArmModel, EndFrame, Pose, damped_least_squares};
use nalgebra::{Vector3, Vector6};
use serde::Serialize;

/// Damping λ of the least-squares map (mixed units: m and rad); as the env's TCP action.
pub const DAMPING: f64 = 0.01;

/// An offset of the grasp, table frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TaskCorrection {
    /// TCP offset along the table frame's x, y, z \[m\].
    pub offset: [f64; 3],
    /// Yaw offset about the table's vertical \[rad\].
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

/// When the gripper closes, as a residual may shift it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CloseTiming {
    /// When the descent arrives (the script's own timing).
    #[default]
    Script,
    /// Now, if the script is descending (advance the close).
    Now,
    /// Not yet: hold open after the descent arrived, up to
    /// [`crate::BaselineConfig::max_close_delay_steps`] (delay the close).
    Wait,
}

/// How far and how fast a learned correction may go, and how it follows the policy.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CorrectionLimits {
    /// Largest offset along the table's x and y \[m\] (5 cm: above the families' 1.5–3 cm errors).
    pub max_offset: f64,
    /// Largest offset along the table's vertical \[m\] (1 cm: the cube lies on the table; more
    /// lets exploration drive the fingers into it).
    pub max_height: f64,
    /// Largest yaw offset \[rad\] (15°: the miscalibrated cells are off by 2–2.5°).
    pub max_yaw: f64,
    /// Fastest the offset may change \[m/s\].
    pub speed: f64,
    /// Fastest the yaw offset may change \[rad/s\].
    pub yaw_rate: f64,
    /// Time constant \[s\] of the first-order filter the correction follows the policy's command
    /// through. It makes the correction persistent between steps, and turns per-step
    /// exploration noise into a slowly varying offset (time-correlated exploration) whose
    /// spread stays bounded: `σ·max·√(α/(2−α))` for `α = dt/τ`.
    pub time_constant: f64,
    /// Squeeze per finger \[N\] added to the env's `gripper.force` at a squeeze command of +1,
    /// when the residual has the squeeze
    /// ([`crate::lift::residual::ResidualScript::squeezing`]). 7 N: 12 N on the default 5 N
    /// grip, which lifts the `heavy_slippery` cubes; at 15 N the fingers' closing impact trips
    /// the 35 N protective stop.
    pub max_squeeze: f64,
}

impl Default for CorrectionLimits {
    fn default() -> Self {
        Self {
            max_offset: 0.05,
            max_height: 0.01,
            max_yaw: 15f64.to_radians(),
            speed: 0.15,
            yaw_rate: 0.5,
            time_constant: 0.4,
            max_squeeze: 7.0,
        }
    }
}

impl CorrectionLimits {
    /// The filter's step gain `α = min(1, dt/τ)` for a step of `dt` \[s\].
    pub fn gain(&self, dt: f64) -> f64 {
        (dt / self.time_constant.max(1e-9)).min(1.0)
    }

    /// `c` one step of `dt` \[s\] closer to the command `action[0..4]` (each clipped to [-1, 1],
    /// × the largest offset and yaw), within the rate limits.
    pub fn follow(&self, c: &TaskCorrection, action: &[f64], dt: f64) -> TaskCorrection {
        let a = |i: usize| action.get(i).copied().unwrap_or(0.0).clamp(-1.0, 1.0);
        let alpha = self.gain(dt);
        let toward = |now: f64, target: f64, rate: f64| {
            let step = ((target - now) * alpha).clamp(-rate * dt, rate * dt);
            now + step
        };
        let max = [self.max_offset, self.max_offset, self.max_height];
        TaskCorrection {
            offset: [0, 1, 2].map(|i| toward(c.offset[i], a(i) * max[i], self.speed)),
            yaw: toward(c.yaw, a(3) * self.max_yaw, self.yaw_rate),
        }
    }

    /// The correction scaled into [-1, 1] per entry (what the policy sees of it; also the
    /// command that holds it).
    pub fn normalized(&self, c: &TaskCorrection) -> [f64; 4] {
        [
            c.offset[0] / self.max_offset,
            c.offset[1] / self.max_offset,
            c.offset[2] / self.max_height,
            c.yaw / self.max_yaw,
        ]
    }
}

/// Newton steps of [`corrected`]: each one cuts the remaining TCP error by a factor of ~100
/// for centimetre offsets.
const NEWTON_STEPS: usize = 3;

/// The joints near `q` \[rad\] that put the TCP where `c` moves it from `fk(q)`: translated by the
/// offset (table frame) and turned about the table's vertical through the TCP by the yaw.
/// `table_in_base` is the table frame in `base_link`. Damped least-squares Newton steps from `q`
/// through the Jacobian; exact to micrometres for the offsets a correction spans (a test checks
/// it).
pub fn corrected(
    model: &ArmModel,
    table_in_base: &Pose,
    q: &[f64; 6],
    c: &TaskCorrection,
) -> [f64; 6] {
    if c.is_zero() {
        return *q;
    }
    let to_base = table_in_base.iso.rotation;
    let up = to_base * Vector3::z();
    let start = model.fk_tcp(q).iso;
    let target_position = start.translation.vector + to_base * Vector3::from(c.offset);
    let target_rotation = nalgebra::UnitQuaternion::from_scaled_axis(up * c.yaw) * start.rotation;
    let mut out = *q;
    for _ in 0..NEWTON_STEPS {
        let now = model.fk_tcp(&out).iso;
        let dp = target_position - now.translation.vector;
        let dr = (target_rotation * now.rotation.inverse()).scaled_axis();
        let error = Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z);
        let j = model.jacobian(&out, EndFrame::Tcp);
        let Some(dq) = damped_least_squares(&j, &error, DAMPING) else {
            return out;
        };
        for (v, d) in out.iter_mut().zip(dq.iter()) {
            *v += d;
        }
    }
    out
}

/// `corrected(q, c) − q` \[rad\].
pub fn joint_offset(
    model: &ArmModel,
    table_in_base: &Pose,
    q: &[f64; 6],
    c: &TaskCorrection,
) -> [f64; 6] {
    let moved = corrected(model, table_in_base, q, c);
    std::array::from_fn(|i| moved[i] - q[i])
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
            assert!((moved - want).norm() < 1e-5, "{moved:?} vs {want:?}");
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
    fn the_correction_follows_the_command_within_its_rate_and_settles_on_it() {
        let limits = CorrectionLimits::default();
        let dt = 1.0 / 12.0;
        let alpha = limits.gain(dt);
        let mut c = TaskCorrection::ZERO;
        c = limits.follow(&c, &[0.2, -0.1, 0.0, 0.4], dt);
        assert!((c.offset[0] - 0.2 * 0.05 * alpha).abs() < 1e-12, "{c:?}");
        assert!((c.offset[1] + 0.1 * 0.05 * alpha).abs() < 1e-12, "{c:?}");
        // A full command is rate-limited when the filter asks for more than the rate allows.
        let slow = CorrectionLimits {
            speed: 0.05,
            ..limits
        };
        let fast = slow.follow(&TaskCorrection::ZERO, &[1.0, 0.0, 0.0, 0.0], dt);
        assert!(0.05 * alpha > slow.speed * dt);
        assert!((fast.offset[0] - slow.speed * dt).abs() < 1e-12, "{fast:?}");
        for _ in 0..200 {
            c = limits.follow(&c, &[5.0, -0.5, 1.0, -1.0], dt);
        }
        assert!((c.offset[0] - 0.05).abs() < 1e-9 && (c.offset[1] + 0.025).abs() < 1e-9);
        assert!((c.offset[2] - limits.max_height).abs() < 1e-9);
        assert!((c.yaw + limits.max_yaw).abs() < 1e-9);
        let n = limits.normalized(&c);
        assert!(
            (n[0] - 1.0).abs() < 1e-9 && (n[2] - 1.0).abs() < 1e-9,
            "{n:?}"
        );
        assert!((n[3] + 1.0).abs() < 1e-9, "{n:?}");
        // A zero command brings it back to no correction.
        for _ in 0..200 {
            c = limits.follow(&c, &[0.0; 4], dt);
        }
        assert!(c.offset.iter().all(|v| v.abs() < 1e-9) && c.yaw.abs() < 1e-9);
    }
}
