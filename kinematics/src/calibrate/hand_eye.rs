//! `base_link ↔ camera` for a camera fixed in the cell (eye-to-hand): a marker is fixed to the
//! gripper, the arm is moved to several poses, and at each the TCP's pose in `base_link`
//! (`G_i`, from FK of the joint readings) and the marker's pose in the camera (`C_i`, from the
//! camera's marker detector) are recorded.
//!
//! Unknown: `X = T_base_camera` and `Y = T_tcp_marker`, with `G_i · Y = X · C_i` for every `i`.
//! For two poses `i`, `j`, eliminating `Y` gives `A·X = X·B` with `A = G_j·G_i⁻¹` and
//! `B = C_j·C_i⁻¹`. Park and Martin (1994): the rotation axis-angle vectors satisfy
//! `α = R_X·β`, so `R_X` is the rotation best aligning every `β` with its `α` (solved as a Kabsch
//! problem, which keeps it a proper rotation); then `(R_A − I)·t_X = R_X·t_B − t_A` is solved for
//! `t_X` by linear least squares. `Y` is the mean of `G_i⁻¹·X·C_i`. Every pair `i < j` is used.

use nalgebra::{Isometry3, Matrix3, Rotation3, UnitQuaternion, Vector3};

use super::{CalibrationError, kabsch, mm, principal_spread};
use crate::Pose;

/// The method, as the output names it.
pub const METHOD: &str = "Park–Martin (1994) AX = XB, eye-to-hand, all pose pairs";

/// One station of the arm: the TCP in `base_link` and the marker in the camera frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandEyeSample {
    /// `G_i = T_base_tcp`.
    pub tcp_in_base: Pose,
    /// `C_i = T_camera_marker`.
    pub marker_in_camera: Pose,
}

/// Bounds of a hand-eye fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandEyeOptions {
    /// The largest accepted position residual of a station \[m\] (default 5 mm).
    pub max_position_residual: f64,
    /// The largest accepted angle residual of a station \[rad\] (default 1°).
    pub max_angle_residual: f64,
    /// Motions rotating less than this \[rad\] carry no axis and are left out of the rotation
    /// solve (default 2°).
    pub min_motion_angle: f64,
    /// Below this spread of the motions' rotation axes off one axis (as a fraction of their
    /// largest) the rotation about that axis is undetermined and the fit is refused (0.05).
    pub min_axis_spread: f64,
}

impl Default for HandEyeOptions {
    fn default() -> Self {
        Self {
            max_position_residual: 0.005,
            max_angle_residual: 1f64.to_radians(),
            min_motion_angle: 2f64.to_radians(),
            min_axis_spread: 0.05,
        }
    }
}

/// The result of a hand-eye fit.
#[derive(Clone, Debug, PartialEq)]
pub struct HandEyeFit {
    /// `X = T_base_camera`: the camera's pose in `base_link`.
    pub camera_in_base: Pose,
    /// `Y = T_tcp_marker`: the marker's pose on the gripper.
    pub marker_in_tcp: Pose,
    /// Per station, the distance between the marker placed by the arm (`G_i·Y`) and by the
    /// camera (`X·C_i`) \[m\].
    pub position_residuals: Vec<f64>,
    /// Per station, the angle between the same two marker orientations \[rad\].
    pub angle_residuals: Vec<f64>,
    /// Root mean squares of the two \[m\], \[rad\].
    pub rms_position: f64,
    pub rms_angle: f64,
    /// Pose pairs used for the rotation (motions rotating enough).
    pub motions_used: usize,
    /// Always [`METHOD`].
    pub method: &'static str,
}

/// What the station errors name.
const WHAT: &str = "station";

/// Fits the camera's pose in `base_link` and the marker's on the gripper (see the module docs).
pub fn fit_eye_to_hand(
    samples: &[HandEyeSample],
    opts: &HandEyeOptions,
) -> Result<HandEyeFit, CalibrationError> {
    check_stations(samples)?;
    let motions = motions(samples);
    let (r_x, motions_used) = camera_rotation(&motions, opts)?;
    let t_x = camera_translation(&motions, &r_x)?;
    let x = Isometry3::from_parts(t_x.into(), UnitQuaternion::from_rotation_matrix(&r_x));
    let y = marker_on_gripper(samples, &x);
    let (position_residuals, angle_residuals) = residuals(samples, &x, &y);
    check_residuals(&position_residuals, &angle_residuals, opts)?;
    let n = samples.len() as f64;
    let rms = |v: &[f64]| (v.iter().map(|r| r * r).sum::<f64>() / n).sqrt();
    Ok(HandEyeFit {
        camera_in_base: Pose { iso: x },
        marker_in_tcp: Pose { iso: y },
        rms_position: rms(&position_residuals),
        rms_angle: rms(&angle_residuals),
        position_residuals,
        angle_residuals,
        motions_used,
        method: METHOD,
    })
}

/// Refuses fewer than three stations, or one holding a non-finite number.
fn check_stations(samples: &[HandEyeSample]) -> Result<(), CalibrationError> {
    if samples.len() < 3 {
        return Err(CalibrationError::TooFew {
            what: "stations (robot pose + marker pose)",
            found: samples.len(),
            needed: 3,
            hint: ": move the arm to three or more poses that turn the marker about different axes",
        });
    }
    let finite = |p: &Pose| p.xyz().iter().chain(&p.quat_xyzw()).all(|v| v.is_finite());
    match samples
        .iter()
        .position(|s| !finite(&s.tcp_in_base) || !finite(&s.marker_in_camera))
    {
        Some(i) => Err(CalibrationError::NonFinite {
            what: WHAT,
            index: i + 1,
        }),
        None => Ok(()),
    }
}

/// The motion `(A, B) = (G_j·G_i⁻¹, C_j·C_i⁻¹)` of every pair of stations `i < j`.
fn motions(samples: &[HandEyeSample]) -> Vec<(Isometry3<f64>, Isometry3<f64>)> {
    (0..samples.len())
        .flat_map(|i| (i + 1..samples.len()).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (gi, gj) = (samples[i].tcp_in_base.iso, samples[j].tcp_in_base.iso);
            let (ci, cj) = (
                samples[i].marker_in_camera.iso,
                samples[j].marker_in_camera.iso,
            );
            (gj * gi.inverse(), cj * ci.inverse())
        })
        .collect()
}

/// `R_X`: `α = R_X·β` for the motions that rotate enough to have an axis, and how many those
/// are; refused when their axes lie along one axis (the rotation about it is undetermined).
fn camera_rotation(
    motions: &[(Isometry3<f64>, Isometry3<f64>)],
    opts: &HandEyeOptions,
) -> Result<(Rotation3<f64>, usize), CalibrationError> {
    let axes: Vec<(Vector3<f64>, Vector3<f64>)> = motions
        .iter()
        .map(|(a, b)| (a.rotation.scaled_axis(), b.rotation.scaled_axis()))
        .filter(|(alpha, _)| alpha.norm() >= opts.min_motion_angle)
        .collect();
    let alphas: Vec<Vector3<f64>> = axes.iter().map(|(a, _)| *a).collect();
    let spread = principal_spread(&alphas);
    if axes.len() < 2 || spread[1] < opts.min_axis_spread * spread[0] {
        return Err(CalibrationError::Degenerate(format!(
            "the arm's motions between stations turn about one axis only ({} of {} motions turn \
             more than {:.1}°; their axes spread {:.3} of the largest off one axis, at least {} \
             needed): the camera's rotation about that axis is undetermined; add stations that \
             tilt the marker about other axes",
            axes.len(),
            motions.len(),
            opts.min_motion_angle.to_degrees(),
            if spread[0] > 0.0 {
                spread[1] / spread[0]
            } else {
                0.0
            },
            opts.min_axis_spread
        )));
    }
    let h: Matrix3<f64> = axes
        .iter()
        .map(|(alpha, beta)| beta * alpha.transpose())
        .sum();
    let (r_x, _) = kabsch(&h);
    Ok((r_x, axes.len()))
}

/// `t_X` \[m\]: `(R_A − I)·t_X = R_X·t_B − t_A` over every motion, stacked, by the normal
/// equations; refused when they do not determine it.
fn camera_translation(
    motions: &[(Isometry3<f64>, Isometry3<f64>)],
    r_x: &Rotation3<f64>,
) -> Result<Vector3<f64>, CalibrationError> {
    let mut ata = Matrix3::<f64>::zeros();
    let mut atb = Vector3::<f64>::zeros();
    for (a, b) in motions {
        let m = a.rotation.to_rotation_matrix().into_inner() - Matrix3::identity();
        let rhs = r_x * b.translation.vector - a.translation.vector;
        ata += m.transpose() * m;
        atb += m.transpose() * rhs;
    }
    ata.cholesky().map(|c| c.solve(&atb)).ok_or_else(|| {
        CalibrationError::Degenerate(
            "the motions do not determine the camera's position (every motion turns about one \
             axis): add stations with other rotations"
                .into(),
        )
    })
}

/// `Y`: the mean of `G_i⁻¹·X·C_i` (translations averaged, rotations by the chordal mean).
fn marker_on_gripper(samples: &[HandEyeSample], x: &Isometry3<f64>) -> Isometry3<f64> {
    let ys: Vec<Isometry3<f64>> = samples
        .iter()
        .map(|s| s.tcp_in_base.iso.inverse() * x * s.marker_in_camera.iso)
        .collect();
    let n = ys.len() as f64;
    let t_y = ys
        .iter()
        .map(|y| y.translation.vector)
        .sum::<Vector3<f64>>()
        / n;
    let sum: Matrix3<f64> = ys
        .iter()
        .map(|y| y.rotation.to_rotation_matrix().into_inner())
        .sum();
    // The rotation nearest to the sum: Kabsch with a = the identity's columns, b = sum's.
    let (r_y, _) = kabsch(&sum.transpose());
    Isometry3::from_parts(t_y.into(), UnitQuaternion::from_rotation_matrix(&r_y))
}

/// Per station, the distance \[m\] and the angle \[rad\] between the marker placed by the arm
/// (`G_i·Y`) and by the camera (`X·C_i`).
fn residuals(
    samples: &[HandEyeSample],
    x: &Isometry3<f64>,
    y: &Isometry3<f64>,
) -> (Vec<f64>, Vec<f64>) {
    samples
        .iter()
        .map(|s| {
            let by_arm = s.tcp_in_base.iso * y;
            let by_camera = x * s.marker_in_camera.iso;
            (
                (by_arm.translation.vector - by_camera.translation.vector).norm(),
                by_arm.rotation.angle_to(&by_camera.rotation),
            )
        })
        .unzip()
}

/// Refuses the first station beyond either bound, naming every station's residuals.
fn check_residuals(
    position_residuals: &[f64],
    angle_residuals: &[f64],
    opts: &HandEyeOptions,
) -> Result<(), CalibrationError> {
    let all = || {
        position_residuals
            .iter()
            .zip(angle_residuals)
            .map(|(p, a)| format!("{} {:.2}°", mm(*p), a.to_degrees()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    for (i, (p, a)) in position_residuals.iter().zip(angle_residuals).enumerate() {
        if *p > opts.max_position_residual || *a > opts.max_angle_residual {
            return Err(CalibrationError::ResidualTooLarge {
                what: WHAT,
                index: i + 1,
                residual: format!("{} and {:.2}°", mm(*p), a.to_degrees()),
                bound: format!(
                    "{} and {:.2}°",
                    mm(opts.max_position_residual),
                    opts.max_angle_residual.to_degrees()
                ),
                all: all(),
            });
        }
    }
    Ok(())
}
