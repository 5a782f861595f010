//! Closed-form inverse kinematics for UR-like arms (FR3, FR5): up to 8 branches.
//!
//! The construction (after Hawkins 2013, re-derived for standard DH with the FR3's negative
//! a2, a3): with `u = z1 = (sin θ1, −cos θ1, 0)` the common direction of joints 2, 3, 4,
//!
//! 1. the origin of frame 5, `p5 = p − d6·z6`, satisfies `p5 · u = d4`, so
//!    `θ1 = ψ + asin(d4/r)` or `ψ + π − asin(d4/r)` with `r, ψ` the polar coordinates of p5;
//! 2. `u` seen from the flange is `(s5·c6, −s5·s6, c5)`, so
//!    `θ5 = atan2(±|(x6·u, y6·u)|, z6·u)` (two wrist branches; the flange then satisfies
//!    `p · u = d4 + d6·cos θ5` by step 1);
//! 3. `θ6 = atan2(−(y6·u)/s5, (x6·u)/s5)`;
//! 4. joints 2, 3 form a planar 2R arm reaching `p13 = p14 − (0, 0, d4)` in frame 1 (two elbow
//!    branches), and `θ4 = θ234 − θ2 − θ3` with `θ234` read from `R14`.
//!
//! Where the wrist is singular (|sin θ5| < 1e-10), joints 2, 3, 4 and 6 are parallel and θ6 is
//! free: it is chosen among the values for which the elbow reaches, the caller's
//! [`AnalyticIkOptions::wrist_singular_q6`] first (see `wrist_singular.rs`), and only the
//! wrist branch θ5 = 0 (or π) is returned, with its two elbows.
//!
//! Each angle is then moved into its joint's limits by adding or subtracting 2π where that helps
//! (j2 and j4 span −265° … +85°), and flagged if no representative is within the limits.

use std::f64::consts::{PI, TAU};

use nalgebra::{Isometry3, Vector3};
use serde::Serialize;

pub use crate::angles::wrap_pi;
use crate::fk::{EndFrame, dh_transform};
use crate::model::ArmModel;
use crate::pose::Pose;
use crate::wrist_singular::singular_wrist_q6_candidates;

/// Below this |sin θ5| the wrist is singular: joints 2, 3, 4 and 6 turn about parallel axes.
/// Choosing θ6 freely there costs at most about this much \[rad, m per m of arm\] in the FK.
const WRIST_SINGULAR_SIN: f64 = 1e-10;
/// acos/asin arguments this far beyond ±1 are treated as rounding and clamped.
const BOUNDARY_SLACK: f64 = 1e-10;

/// One IK branch.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct IkSolution {
    /// Joint angles j1 … j6 \[rad\], each moved into its limits where a 2π shift allows.
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
        /// Horizontal distance of the wrist centre from the joint-1 axis \[m\].
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
    /// θ6 to prefer where the wrist is singular (θ5 = 0 or π) and θ6 is free \[rad\]. Used as is
    /// where the elbow then reaches the target and the joints are within their limits; else the
    /// nearest θ6 for which they are (or at least the elbow reaches).
    pub wrist_singular_q6: f64,
    /// Tolerance on the joint-limit check \[rad\].
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
            // 2. Wrist 2: u = z1 seen from the flange is (s5·c6, −s5·s6, c5). θ5 is read as an
            //    atan2 of both, accurate near 0 and π where acos(c5) alone loses half the digits
            //    (and p · u = d4 + d6·c5 holds by step 1, so this is the same θ5).
            let u = Vector3::new(s1, -c1, 0.0);
            let (ux, uy, uz) = (x6.dot(&u), y6.dot(&u), z6.dot(&u));
            let s5_abs = ux.hypot(uy);
            if s5_abs < WRIST_SINGULAR_SIN {
                let q5 = if uz >= 0.0 { 0.0 } else { PI };
                match self.singular_wrist_branch(&t16, q1, q5, options) {
                    Ok(pair) => solutions.extend(pair.into_iter().enumerate().map(
                        |(elbow_bit, (joints, in_limits))| IkSolution {
                            joints,
                            in_limits,
                            branch: shoulder_bit as u8 | (elbow_bit as u8) << 2,
                        },
                    )),
                    Err(reason) => last_failure = reason,
                }
                continue;
            }
            for (wrist_bit, sign) in [1.0, -1.0].into_iter().enumerate() {
                let q5 = (sign * s5_abs).atan2(uz);
                // 3. Wrist 3 from u seen in the flange frame.
                let q6 = (-sign * uy).atan2(sign * ux);
                match self.elbow_branches(&t16, q1, q5, q6) {
                    Ok(pair) => {
                        for (elbow_bit, raw) in pair.into_iter().enumerate() {
                            let (joints, in_limits) =
                                self.wrap_into_limits(raw, options.limit_tolerance);
                            solutions.push(IkSolution {
                                joints,
                                in_limits,
                                branch: shoulder_bit as u8
                                    | (wrist_bit as u8) << 1
                                    | (elbow_bit as u8) << 2,
                            });
                        }
                    }
                    Err(reason) => last_failure = reason,
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

    /// Step 4 for one shoulder and wrist: the planar 2R arm of joints 2, 3 (both elbows) and θ4
    /// from the remaining rotation. `t16` is the flange in frame 1; angles \[rad\]. Returns the two
    /// raw joint vectors (elbow bit 0, 1), or why the elbow cannot reach.
    fn elbow_branches(
        &self,
        t16: &Isometry3<f64>,
        q1: f64,
        q5: f64,
        q6: f64,
    ) -> Result<[[f64; 6]; 2], String> {
        let (a2, a3) = (self.dh[1].a, self.dh[2].a);
        let t14 = self.frame4_in_frame1(t16, q5, q6);
        let p13 = t14.translation.vector - Vector3::new(0.0, 0.0, self.dh[3].d);
        let reach_sq = p13.x * p13.x + p13.y * p13.y;
        let Some(c3) = clamp_unit((reach_sq - a2 * a2 - a3 * a3) / (2.0 * a2 * a3)) else {
            let (shortest, longest) = self.elbow_span();
            return Err(format!(
                "the elbow cannot span {:.4} m (links reach {shortest:.3} … {longest:.3} m)",
                reach_sq.sqrt()
            ));
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
        Ok([(q3_abs, s3_abs), (-q3_abs, -s3_abs)].map(|(q3, s3)| {
            let q2 = towards_wrist - (a3 * s3).atan2(a2 + a3 * c3);
            [q1, q2, q3, q234 - q2 - q3, q5, q6]
        }))
    }

    /// Both elbows at a singular wrist (θ5 = `q5`, 0 or π): θ6 is free, so the first θ6 from
    /// [`singular_wrist_q6_candidates`] (the caller's `wrist_singular_q6` where the elbow
    /// reaches) whose solution has an elbow within all joint limits, else the first that
    /// reaches at all. Each pair is (joints \[rad\], in limits?).
    fn singular_wrist_branch(
        &self,
        t16: &Isometry3<f64>,
        q1: f64,
        q5: f64,
        options: &AnalyticIkOptions,
    ) -> Result<[([f64; 6], bool); 2], String> {
        let d4 = self.dh[3].d;
        let reach_sq = |q6| {
            let p14 = self.frame4_in_frame1(t16, q5, q6).translation.vector;
            let p13 = p14 - Vector3::new(0.0, 0.0, d4);
            p13.x * p13.x + p13.y * p13.y
        };
        let (shortest, longest) = self.elbow_span();
        let range = (shortest * shortest, longest * longest);
        let candidates = singular_wrist_q6_candidates(options.wrist_singular_q6, reach_sq, range);
        let mut first_reaching = None;
        for q6 in candidates {
            let Ok(pair) = self.elbow_branches(t16, q1, q5, q6) else {
                continue;
            };
            let pair = pair.map(|raw| self.wrap_into_limits(raw, options.limit_tolerance));
            if pair.iter().any(|&(_, in_limits)| in_limits) {
                return Ok(pair);
            }
            first_reaching.get_or_insert(pair);
        }
        first_reaching.ok_or_else(|| {
            format!(
                "the wrist is singular (joint 5 at {:.0}°) and for no joint-6 angle can the elbow \
                 span the distance (links reach {shortest:.3} … {longest:.3} m)",
                q5.to_degrees()
            )
        })
    }

    /// `T_1_4`: frame 4 in frame 1, from the flange in frame 1 and θ5, θ6 \[rad\].
    fn frame4_in_frame1(&self, t16: &Isometry3<f64>, q5: f64, q6: f64) -> Isometry3<f64> {
        let t45 = dh_transform(&self.dh[4], q5);
        let t56 = dh_transform(&self.dh[5], q6);
        t16 * (t45 * t56).inverse()
    }

    /// Shortest and longest distance the elbow (links a2, a3) spans \[m\].
    fn elbow_span(&self) -> (f64, f64) {
        let (a2, a3) = (self.dh[1].a.abs(), self.dh[2].a.abs());
        ((a2 - a3).abs(), a2 + a3)
    }

    /// Each angle moved into its joint's limits where a 2π shift allows; and are all within?
    fn wrap_into_limits(&self, raw: [f64; 6], tolerance: f64) -> ([f64; 6], bool) {
        let mut joints = [0.0; 6];
        let mut in_limits = true;
        for (i, spec) in self.joints.iter().enumerate() {
            let (q, ok) = into_limits(raw[i], spec.lower, spec.upper, tolerance);
            joints[i] = q;
            in_limits &= ok;
        }
        (joints, in_limits)
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

/// Euclidean distance between two joint vectors \[rad\].
pub fn joint_distance(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
