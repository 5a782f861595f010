//! Frame calibration from measurements: where the arm's base stands in the world, and where a
//! fixed camera stands relative to the base, solved from what an engineer can measure in a cell.
//!
//! - [`points`]: `world ↔ base_link` from point pairs (the TCP touched to known world points):
//!   closed form (Kabsch / Umeyama without scale), then Gauss–Newton least squares.
//! - [`hand_eye`]: `base_link ↔ camera` for a camera fixed in the cell (eye-to-hand) from robot
//!   poses and the marker poses the camera saw: Park–Martin's `AX = XB`.
//!
//! Every fit reports the residual of every measurement and refuses, naming the measurement, when
//! one is beyond a stated bound, when there are too few, or when they cannot determine the
//! answer (collinear points, rotations about one axis only). Lengths are metres, angles radians.

pub mod hand_eye;
pub mod points;

pub use hand_eye::{HandEyeFit, HandEyeOptions, HandEyeSample, fit_eye_to_hand};
pub use points::{PointFit, PointFitOptions, PointPair, fit_points};

use nalgebra::{Matrix3, Rotation3};

/// Why a calibration was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    /// Fewer measurements than the fit needs.
    #[error("{found} {what} given; at least {needed} are needed{hint}")]
    TooFew {
        /// "point pairs" or "pose pairs".
        what: &'static str,
        found: usize,
        needed: usize,
        /// What to measure next.
        hint: &'static str,
    },
    /// A measurement holds NaN or an infinite number.
    #[error("{what} {index} (counting from 1) holds a non-finite number")]
    NonFinite {
        what: &'static str,
        /// 1-based, as a person counts rows.
        index: usize,
    },
    /// The measurements cannot determine the answer.
    #[error("{0}")]
    Degenerate(String),
    /// The two sides of the point pairs differ in size: a unit mistake.
    #[error(
        "the world points are {scale:.4}× the size of the base points (a rigid transform keeps sizes; \
         allowed 1 ± {tolerance}): are both in metres?"
    )]
    ScaleMismatch { scale: f64, tolerance: f64 },
    /// The best fit still leaves a measurement too far off.
    #[error(
        "{what} {index} (counting from 1) is {residual} off after the best fit, beyond the bound of \
         {bound}: a mistyped or mis-touched measurement? (every residual: {all})"
    )]
    ResidualTooLarge {
        what: &'static str,
        index: usize,
        residual: String,
        bound: String,
        all: String,
    },
}

/// The proper rotation `R` minimising `Σ |R·a_k − b_k|²` given `h = Σ a_k b_kᵀ` (Kabsch: the SVD
/// `h = U S Vᵀ`, `R = V diag(1, 1, det(V Uᵀ)) Uᵀ`), and the singular values of `h`.
fn kabsch(h: &Matrix3<f64>) -> (Rotation3<f64>, [f64; 3]) {
    let svd = h.svd(true, true);
    let (u, v_t) = (
        svd.u.expect("SVD with U asked for"),
        svd.v_t.expect("SVD with Vᵀ asked for"),
    );
    let v = v_t.transpose();
    let d = (v * u.transpose()).determinant().signum();
    let r = v * Matrix3::from_diagonal(&nalgebra::Vector3::new(1.0, 1.0, d)) * u.transpose();
    let s = svd.singular_values;
    (Rotation3::from_matrix_unchecked(r), [s[0], s[1], s[2]])
}

/// The spread of a centred set of vectors along its principal axes, largest first: the square
/// roots of the eigenvalues of `Σ v vᵀ / n` (the RMS distance from the centroid along each axis).
fn principal_spread(centred: &[nalgebra::Vector3<f64>]) -> [f64; 3] {
    let n = centred.len().max(1) as f64;
    let cov: Matrix3<f64> = centred
        .iter()
        .map(|v| v * v.transpose())
        .sum::<Matrix3<f64>>()
        / n;
    let mut e: Vec<f64> = cov
        .symmetric_eigenvalues()
        .iter()
        .map(|l| l.max(0.0).sqrt())
        .collect();
    e.sort_by(|a, b| b.total_cmp(a));
    [e[0], e[1], e[2]]
}

/// Millimetres with one decimal, for messages.
fn mm(metres: f64) -> String {
    format!("{:.1} mm", metres * 1000.0)
}
