//! `world ↔ base_link` from point pairs: the TCP touched to ≥ 3 points whose world coordinates
//! are known (marks on the table, a fixture's corners), each touch giving the same point in
//! `base_link` (from the joint readings through FK, or the TCP position the controller shows).
//!
//! The answer is `T_world_base`, the mount the env config's `[arm]` table holds (`base_xyz`,
//! `base_rpy`): `p_world = T_world_base · p_base` for every pair, up to measurement error.
//! Solved in closed form (Kabsch; Umeyama's scale is computed only to refuse a unit mistake),
//! then refined by Gauss–Newton on the same squared distances.

use nalgebra::{Matrix3, Matrix6, Rotation3, Vector3, Vector6};

use super::{CalibrationError, kabsch, mm, principal_spread};
use crate::Pose;

/// One touched point: the same physical point in both frames \[m\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointPair {
    /// Its known coordinates in the world (or table) frame \[m\].
    pub world: [f64; 3],
    /// The TCP's position in `base_link` when it touched the point \[m\].
    pub base: [f64; 3],
}

/// Bounds of a point fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointFitOptions {
    /// The largest residual accepted for any point \[m\] (default 5 mm: FR3 repeatability is
    /// ±0.02 mm; a careful touch with a pointed tool is within 1–2 mm).
    pub max_residual: f64,
    /// Below this spread of the points off their best line \[m\], the rotation about that line is
    /// poorly determined and the fit warns (default 5 cm).
    pub warn_spread: f64,
    /// Below this spread off their best line \[m\] the points are collinear and refused (1 mm).
    pub min_spread: f64,
    /// The largest accepted `|scale − 1|` of the Umeyama fit with scale (default 0.05).
    pub scale_tolerance: f64,
}

impl Default for PointFitOptions {
    fn default() -> Self {
        Self {
            max_residual: 0.005,
            warn_spread: 0.05,
            min_spread: 0.001,
            scale_tolerance: 0.05,
        }
    }
}

/// The result of a point fit.
#[derive(Clone, Debug, PartialEq)]
pub struct PointFit {
    /// `T_world_base`: where `base_link` stands in the world.
    pub base_in_world: Pose,
    /// `|T·p_base − p_world|` of every pair, in input order \[m\].
    pub residuals: Vec<f64>,
    /// Root mean square of the residuals \[m\].
    pub rms: f64,
    /// The closed form's RMS before the least-squares refinement \[m\].
    pub closed_form_rms: f64,
    /// Gauss–Newton iterations the refinement took.
    pub iterations: usize,
    /// Umeyama's scale (world size / base size); 1 for consistent units.
    pub scale: f64,
    /// Spread of the base points along their principal axes, largest first \[m\].
    pub spread: [f64; 3],
    /// What the fit could do but a person should know (nearly collinear points, only three).
    pub warnings: Vec<String>,
}

/// What the point pair errors name.
const WHAT: &str = "point pair";

/// Fits `T_world_base` to the point pairs (see the module docs).
pub fn fit_points(
    pairs: &[PointPair],
    opts: &PointFitOptions,
) -> Result<PointFit, CalibrationError> {
    check_pairs(pairs)?;
    let world: Vec<Vector3<f64>> = pairs.iter().map(|p| Vector3::from(p.world)).collect();
    let base: Vec<Vector3<f64>> = pairs.iter().map(|p| Vector3::from(p.base)).collect();
    let n = pairs.len() as f64;
    let closed = closed_form(&base, &world, opts)?;
    let closed_form_rms =
        (squared_distances(&base, &world, &closed.rotation, &closed.translation) / n).sqrt();
    let (rotation, translation, iterations) =
        refine(&base, &world, closed.rotation, closed.translation);

    let residuals: Vec<f64> = base
        .iter()
        .zip(&world)
        .map(|(b, w)| (rotation * b + translation - w).norm())
        .collect();
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / n).sqrt();
    check_residuals(&residuals, opts)?;
    let iso = nalgebra::Isometry3::from_parts(
        translation.into(),
        nalgebra::UnitQuaternion::from_rotation_matrix(&rotation),
    );
    Ok(PointFit {
        base_in_world: Pose { iso },
        residuals,
        rms,
        closed_form_rms,
        iterations,
        scale: closed.scale,
        spread: closed.spread,
        warnings: warnings(pairs.len(), &closed.spread, opts),
    })
}

/// Refuses fewer than three pairs, or one holding a non-finite number.
fn check_pairs(pairs: &[PointPair]) -> Result<(), CalibrationError> {
    if pairs.len() < 3 {
        return Err(CalibrationError::TooFew {
            what: "point pairs",
            found: pairs.len(),
            needed: 3,
            hint: ": touch three or more points that are not on one line",
        });
    }
    match pairs
        .iter()
        .position(|p| p.world.iter().chain(&p.base).any(|v| !v.is_finite()))
    {
        Some(i) => Err(CalibrationError::NonFinite {
            what: WHAT,
            index: i + 1,
        }),
        None => Ok(()),
    }
}

/// The closed-form fit and what it tells of the points.
struct ClosedForm {
    rotation: Rotation3<f64>,
    /// \[m\]
    translation: Vector3<f64>,
    /// Umeyama's scale (world size / base size).
    scale: f64,
    /// Spread of the base points along their principal axes, largest first \[m\].
    spread: [f64; 3],
}

/// Kabsch on the centred points, refused when they lie on one line or when Umeyama's scale says
/// the two sides are in different units.
fn closed_form(
    base: &[Vector3<f64>],
    world: &[Vector3<f64>],
    opts: &PointFitOptions,
) -> Result<ClosedForm, CalibrationError> {
    let n = base.len() as f64;
    let cw = world.iter().sum::<Vector3<f64>>() / n;
    let cb = base.iter().sum::<Vector3<f64>>() / n;
    let xb: Vec<Vector3<f64>> = base.iter().map(|b| b - cb).collect();
    let xw: Vec<Vector3<f64>> = world.iter().map(|w| w - cw).collect();

    let spread = principal_spread(&xb);
    if spread[1] < opts.min_spread {
        return Err(CalibrationError::Degenerate(format!(
            "the touched points lie on one line (they spread {} off it): the rotation about that \
             line is undetermined; touch a point away from the line",
            mm(spread[1])
        )));
    }
    let h: Matrix3<f64> = xb.iter().zip(&xw).map(|(b, w)| b * w.transpose()).sum();
    let (rotation, singular) = kabsch(&h);
    // Umeyama's scale for the same rotation: trace(S·D) / Σ|b − b̄|², D = diag(1, 1, ±1).
    let d = if h.determinant() < 0.0 { -1.0 } else { 1.0 };
    let variance: f64 = xb.iter().map(|b| b.norm_squared()).sum();
    let scale = (singular[0] + singular[1] + d * singular[2]) / variance;
    if (scale - 1.0).abs() > opts.scale_tolerance {
        return Err(CalibrationError::ScaleMismatch {
            scale,
            tolerance: opts.scale_tolerance,
        });
    }
    Ok(ClosedForm {
        rotation,
        translation: cw - rotation * cb,
        scale,
        spread,
    })
}

/// Refuses the worst pair beyond `max_residual`, naming every pair's residual.
fn check_residuals(residuals: &[f64], opts: &PointFitOptions) -> Result<(), CalibrationError> {
    match residuals
        .iter()
        .enumerate()
        .filter(|(_, r)| **r > opts.max_residual)
        .max_by(|a, b| a.1.total_cmp(b.1))
    {
        Some((i, r)) => Err(CalibrationError::ResidualTooLarge {
            what: WHAT,
            index: i + 1,
            residual: mm(*r),
            bound: mm(opts.max_residual),
            all: residuals
                .iter()
                .map(|r| mm(*r))
                .collect::<Vec<_>>()
                .join(", "),
        }),
        None => Ok(()),
    }
}

/// What a person should know of an accepted fit: only three pairs, or nearly collinear points.
fn warnings(pairs: usize, spread: &[f64; 3], opts: &PointFitOptions) -> Vec<String> {
    let mut warnings = Vec::new();
    if pairs == 3 {
        warnings.push(
            "three points leave little to check a touch by (a misplaced one shifts the answer \
             without a large residual): touch four or more"
                .to_string(),
        );
    }
    if spread[1] < opts.warn_spread {
        warnings.push(format!(
            "the points are nearly on one line (spread {} off it, below {}): the rotation about \
             that line is poorly determined; touch points further apart",
            mm(spread[1]),
            mm(opts.warn_spread)
        ));
    }
    warnings
}

/// `Σ |R·b + t − w|²` over the pairs \[m²\]: what the fit minimises.
fn squared_distances(
    base: &[Vector3<f64>],
    world: &[Vector3<f64>],
    r: &Rotation3<f64>,
    t: &Vector3<f64>,
) -> f64 {
    base.iter()
        .zip(world)
        .map(|(b, w)| (r * b + t - w).norm_squared())
        .sum()
}

/// Gauss–Newton on `Σ |R·b + t − w|²` from the closed form, with `R ← exp(δθ)·R`, `t ← t + δt`;
/// a step is kept only if it lowers the cost. Returns the refined pose and the steps taken.
fn refine(
    base: &[Vector3<f64>],
    world: &[Vector3<f64>],
    mut r: Rotation3<f64>,
    mut t: Vector3<f64>,
) -> (Rotation3<f64>, Vector3<f64>, usize) {
    let mut current = squared_distances(base, world, &r, &t);
    for iteration in 0..20 {
        let mut jtj = Matrix6::<f64>::zeros();
        let mut jtr = Vector6::<f64>::zeros();
        for (b, w) in base.iter().zip(world) {
            let rb = r * b;
            let residual = rb + t - w;
            // ∂residual/∂δθ = −[R·b]×, ∂residual/∂δt = I.
            let mut j = nalgebra::Matrix3x6::<f64>::zeros();
            j.fixed_view_mut::<3, 3>(0, 0)
                .copy_from(&(-rb.cross_matrix()));
            j.fixed_view_mut::<3, 3>(0, 3)
                .copy_from(&Matrix3::identity());
            jtj += j.transpose() * j;
            jtr += j.transpose() * residual;
        }
        let Some(step) = jtj.cholesky().map(|c| c.solve(&(-jtr))) else {
            return (r, t, iteration);
        };
        let r_new = Rotation3::from_scaled_axis(step.fixed_rows::<3>(0).into_owned()) * r;
        let t_new = t + step.fixed_rows::<3>(3);
        let next = squared_distances(base, world, &r_new, &t_new);
        if next >= current || step.norm() < 1e-15 {
            return (r, t, iteration);
        }
        (r, t, current) = (r_new, t_new, next);
    }
    (r, t, 20)
}
