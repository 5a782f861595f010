//! Closed-form inverse kinematics for UR-like arms (FR3, FR5): up to 8 branches.
//!
//! The construction (after Hawkins 2013, re-derived for standard DH with the FR3's negative
//! a2, a3): with `u = z1 = (sin θ1, −cos θ1, 0)` the common direction of joints 2, 3, 4,
//!
//! 1. the origin of frame 5, `p5 = p − d6·z6`, satisfies `p5 · u = d4`, so
//!    `θ1 = ψ + asin(d4/r)` or `ψ + π − asin(d4/r)` with `r, ψ` the polar coordinates of p5;
//! 2. the flange satisfies `p · u = d4 + d6·cos θ5`, so `θ5 = ±acos((p·u − d4)/d6)`;
//! 3. `u` seen from the flange is `(s5·c6, −s5·s6, c5)`, so `θ6 = atan2(−(y6·u)/s5, (x6·u)/s5)`;
//! 4. joints 2, 3 form a planar 2R arm reaching `p13 = p14 − (0, 0, d4)` in frame 1 (two elbow
//!    branches), and `θ4 = θ234 − θ2 − θ3` with `θ234` read from `R14`.
//!
//! Each angle is then moved into its joint's limits by adding or subtracting 2π where that helps
//! (j2 and j4 span −265° … +85°), and flagged if no representative is within the limits.

use std::f64::consts::{PI, TAU};

use nalgebra::{Isometry3, Vector3};
use serde::Serialize;

use crate::fk::{EndFrame, dh_transform};
use crate::model::ArmModel;
use crate::pose::Pose;

/// Below this |sin θ5| the wrist is singular: θ4 and θ6 turn about the same axis.
const WRIST_SINGULAR_SIN: f64 = 1e-10;
/// acos/asin arguments this far beyond ±1 are treated as rounding and clamped.
const BOUNDARY_SLACK: f64 = 1e-10;

/// One IK branch.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct IkSolution {
    /// Joint angles j1 … j6 [rad], each moved into its limits where a 2π shift allows.
    pub joints: [f64; 6],
    /// Are all six within the joint limits?
    pub in_limits: bool,
    /// Which branch: bit 0 shoulder (θ1), bit 1 wrist (sign of θ5), bit 2 elbow (sign of θ3).
    pub branch: u8,
}

/// Why a pose has no IK solution.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum IkError {
    /// The target has NaN or infinite components.
    #[error("the target pose is not finite")]
    NonFinite,
    /// The wrist centre lies on the joint-1 axis: θ1 is undefined.
    #[error(
        "shoulder singular: the wrist centre is on the joint-1 axis ({radius_m:.4} m from it), so joint 1 is undefined"
    )]
    ShoulderSingular {
        /// Horizontal distance of the wrist centre from the joint-1 axis [m].
        radius_m: f64,
    },
    /// The pose cannot be reached: the reason names which geometric condition failed.
    #[error("out of reach: {reason}")]
    OutOfReach {
        /// Human-readable geometric reason, with the numbers.
        reason: String,
    },
}

/// Options of the closed-form solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticIkOptions {
    /// θ6 to use where the wrist is singular (θ5 = 0 or π), when only θ4 + θ6 is determined [rad].
    pub wrist_singular_q6: f64,
    /// Tolerance on the joint-limit check [rad].
    pub limit_tolerance: f64,
}

impl Default for AnalyticIkOptions {
    fn default() -> Self {
        Self {
            wrist_singular_q6: 0.0,
            limit_tolerance: 1e-9,
        }
    }
}

/// Wraps an angle into (−π, π].
pub fn wrap_pi(angle: f64) -> f64 {
    if angle > -PI && angle <= PI {
        return angle; // the common case: atan2 and acos results
    }
    let a = angle.rem_euclid(TAU);
    if a > PI { a - TAU } else { a }
}

/// The representative of `angle` (mod 2π) within `[lower, upper]`, if any; else `angle` wrapped
/// into (−π, π].
fn into_limits(angle: f64, lower: f64, upper: f64, tolerance: f64) -> (f64, bool) {
    let base = wrap_pi(angle);
    for candidate in [base, base - TAU, base + TAU] {
        if candidate >= lower - tolerance && candidate <= upper + tolerance {
            return (candidate, true);
        }
    }
    (base, false)
}

fn clamp_unit(x: f64) -> Option<f64> {
    if x.abs() <= 1.0 {
        Some(x)
    } else if x.abs() <= 1.0 + BOUNDARY_SLACK {
        Some(x.signum())
    } else {
        None
    }
}

impl ArmModel {
    /// Every closed-form IK branch (up to 8) placing `frame` at `target` (in `base_link`).
    pub fn ik_analytic(
        &self,
        target: &Pose,
        frame: EndFrame,
        options: &AnalyticIkOptions,
    ) -> Result<Vec<IkSolution>, IkError> {
        let flange = match frame {
            EndFrame::Flange => *target,
            EndFrame::Tcp => target.compose(&self.tcp_in_flange.inverse()),
        };
        self.ik_flange(&flange.iso, options)
    }

    /// The in-limit branch nearest to `current` (Euclidean distance in joint space), if any.
    pub fn ik_nearest(
        &self,
        target: &Pose,
        frame: EndFrame,
        current: &[f64; 6],
    ) -> Result<Option<IkSolution>, IkError> {
        let options = AnalyticIkOptions {
            wrist_singular_q6: current[5],
            ..AnalyticIkOptions::default()
        };
        let solutions = self.ik_analytic(target, frame, &options)?;
        Ok(nearest_solution(&solutions, current))
    }

    fn ik_flange(
        &self,
        t06: &Isometry3<f64>,
        options: &AnalyticIkOptions,
    ) -> Result<Vec<IkSolution>, IkError> {
        let p = t06.translation.vector;
        let rot = t06.rotation.to_rotation_matrix();
        let (x6, y6, z6) = (
            rot.matrix().column(0).into_owned(),
            rot.matrix().column(1).into_owned(),
            rot.matrix().column(2).into_owned(),
        );
        if !(p.iter().chain(rot.matrix().iter()).all(|v| v.is_finite())) {
            return Err(IkError::NonFinite);
        }
        let (d4, d6) = (self.dh[3].d, self.dh[5].d);
        let (a2, a3) = (self.dh[1].a, self.dh[2].a);

        // 1. Shoulder: p5 · u = d4.
        let p5 = p - d6 * z6;
        let r = p5.x.hypot(p5.y);
        if r < 1e-12 {
            return Err(IkError::ShoulderSingular { radius_m: r });
        }
        let Some(ratio) = clamp_unit(d4 / r) else {
            return Err(IkError::OutOfReach {
                reason: format!(
                    "the wrist centre is {r:.4} m from the joint-1 axis, inside the d4 = {d4:.3} m offset cylinder"
                ),
            });
        };
        let psi = p5.y.atan2(p5.x);
        let offset = ratio.asin();
        let shoulders = [psi + PI - offset, psi + offset];

        let mut solutions = Vec::with_capacity(8);
        let mut last_failure = String::new();
        for (shoulder_bit, &q1) in shoulders.iter().enumerate() {
            let (s1, c1) = q1.sin_cos();
            let t16 = dh_transform(&self.dh[0], q1).inverse() * t06;
            let u = Vector3::new(s1, -c1, 0.0);
            // 2. Wrist 2: p · u = d4 + d6 cos θ5.
            let Some(c5) = clamp_unit((p.dot(&u) - d4) / d6) else {
                last_failure = format!(
                    "the flange is {:.4} m off the arm plane, more than d4 + d6 = {:.3} m",
                    p.dot(&u).abs(),
                    d4 + d6
                );
                continue;
            };
            let q5_abs = c5.acos();
            for (wrist_bit, q5) in [q5_abs, -q5_abs].into_iter().enumerate() {
                let s5 = q5.sin();
                // 3. Wrist 3 from u seen in the flange frame.
                let q6 = if s5.abs() < WRIST_SINGULAR_SIN {
                    options.wrist_singular_q6
                } else {
                    (-(y6.dot(&u)) / s5).atan2(x6.dot(&u) / s5)
                };
                // 4. Planar 2R for joints 2, 3; θ4 from the remaining rotation.
                let t45 = dh_transform(&self.dh[4], q5);
                let t56 = dh_transform(&self.dh[5], q6);
                let t14 = t16 * (t45 * t56).inverse();
                let p13 = t14.translation.vector - Vector3::new(0.0, 0.0, d4);
                let reach_sq = p13.x * p13.x + p13.y * p13.y;
                let Some(c3) = clamp_unit((reach_sq - a2 * a2 - a3 * a3) / (2.0 * a2 * a3)) else {
                    last_failure = format!(
                        "the elbow cannot span {:.4} m (links reach {:.3} … {:.3} m)",
                        reach_sq.sqrt(),
                        (a2.abs() - a3.abs()).abs(),
                        a2.abs() + a3.abs()
                    );
                    continue;
                };
                // θ2 + θ3 + θ4 from R14's first column, read off the quaternion directly.
                let r = t14.rotation.coords; // [x, y, z, w]
                let (r00, r10) = (
                    1.0 - 2.0 * (r.y * r.y + r.z * r.z),
                    2.0 * (r.x * r.y + r.w * r.z),
                );
                let q234 = r10.atan2(r00);
                let q3_abs = c3.acos();
                let s3_abs = (1.0 - c3 * c3).max(0.0).sqrt();
                let towards_wrist = p13.y.atan2(p13.x);
                for (elbow_bit, (q3, s3)) in [(q3_abs, s3_abs), (-q3_abs, -s3_abs)]
                    .into_iter()
                    .enumerate()
                {
                    let q2 = towards_wrist - (a3 * s3).atan2(a2 + a3 * c3);
                    let q4 = q234 - q2 - q3;
                    let raw = [q1, q2, q3, q4, q5, q6];
                    let mut joints = [0.0; 6];
                    let mut in_limits = true;
                    for i in 0..6 {
                        let spec = &self.joints[i];
                        let (q, ok) =
                            into_limits(raw[i], spec.lower, spec.upper, options.limit_tolerance);
                        joints[i] = q;
                        in_limits &= ok;
                    }
                    solutions.push(IkSolution {
                        joints,
                        in_limits,
                        branch: shoulder_bit as u8
                            | (wrist_bit as u8) << 1
                            | (elbow_bit as u8) << 2,
                    });
                }
            }
        }
        if solutions.is_empty() {
            return Err(IkError::OutOfReach {
                reason: last_failure,
            });
        }
        Ok(solutions)
    }
}

/// The in-limit solution nearest to `current` (Euclidean joint distance), if any.
pub fn nearest_solution(solutions: &[IkSolution], current: &[f64; 6]) -> Option<IkSolution> {
    solutions
        .iter()
        .filter(|s| s.in_limits)
        .min_by(|a, b| {
            joint_distance(&a.joints, current).total_cmp(&joint_distance(&b.joints, current))
        })
        .copied()
}

/// Euclidean distance between two joint vectors [rad].
pub fn joint_distance(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
