//! Frame calibration for Python (`fairgrasp.kinematics.calibrate_points`, `calibrate_hand_eye`),
//! NumPy in, dicts out: the same fits as `fairgrasp calibrate points|hand-eye`
//! (`fairgrasp_kinematics::calibrate`). Lengths in metres, angles in radians, poses as
//! `[x, y, z, roll, pitch, yaw]` (URDF fixed-axis); a refusal is a `ValueError` with the
//! library's message.

use fairgrasp_kinematics::Pose;
use fairgrasp_kinematics::calibrate::{
    HandEyeOptions, HandEyeSample, PointFitOptions, PointPair, fit_eye_to_hand, fit_points,
};
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

/// The rows of an `[n, width]` array, checked for shape (finiteness is the library's check).
fn rows(array: &PyReadonlyArray2<'_, f64>, width: usize, what: &str) -> PyResult<Vec<Vec<f64>>> {
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != width {
        return Err(value_error(format!(
            "{what} has shape {shape:?}, expected [n, {width}]"
        )));
    }
    let a = array.as_array();
    Ok(a.rows().into_iter().map(|r| r.to_vec()).collect())
}

fn pose_list(p: &Pose) -> Vec<f64> {
    let (x, r) = (p.xyz(), p.rpy());
    vec![x[0], x[1], x[2], r[0], r[1], r[2]]
}

fn pose_of(row: &[f64]) -> Pose {
    Pose::from_xyz_rpy([row[0], row[1], row[2]], [row[3], row[4], row[5]])
}

/// `world ↔ base_link` from point pairs: `world_points[i]` and `base_points[i]` ([n, 3] each,
/// metres) are one touched point in the two frames. Returns `base_in_world` (the env config's
/// `[arm] base_xyz + base_rpy`), `residuals`, `rms`, `scale`, `warnings`.
#[pyfunction]
#[pyo3(signature = (world_points, base_points, max_residual = 0.005))]
pub(crate) fn calibrate_points<'py>(
    py: Python<'py>,
    world_points: PyReadonlyArray2<'py, f64>,
    base_points: PyReadonlyArray2<'py, f64>,
    max_residual: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let world = rows(&world_points, 3, "world_points")?;
    let base = rows(&base_points, 3, "base_points")?;
    if world.len() != base.len() {
        return Err(value_error(format!(
            "{} world points and {} base points: give them in pairs",
            world.len(),
            base.len()
        )));
    }
    if !(max_residual.is_finite() && max_residual > 0.0 && max_residual <= 1.0) {
        return Err(value_error(format!(
            "max_residual = {max_residual}: must be in (0, 1] m"
        )));
    }
    let pairs: Vec<PointPair> = world
        .iter()
        .zip(&base)
        .map(|(w, b)| PointPair {
            world: [w[0], w[1], w[2]],
            base: [b[0], b[1], b[2]],
        })
        .collect();
    let opts = PointFitOptions {
        max_residual,
        ..PointFitOptions::default()
    };
    let fit = fit_points(&pairs, &opts).map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("base_in_world", pose_list(&fit.base_in_world))?;
    out.set_item("residuals", fit.residuals)?;
    out.set_item("rms", fit.rms)?;
    out.set_item("scale", fit.scale)?;
    out.set_item("warnings", fit.warnings)?;
    Ok(out)
}

/// `base_link ↔` a camera fixed in the cell (eye-to-hand, Park–Martin): `tcp_poses[i]` the TCP
/// in base_link and `marker_poses[i]` the marker in the camera at station `i` ([n, 6] each).
/// Returns `camera_in_base`, `marker_in_tcp`, `position_residuals`, `angle_residuals`, `method`.
#[pyfunction]
pub(crate) fn calibrate_hand_eye<'py>(
    py: Python<'py>,
    tcp_poses: PyReadonlyArray2<'py, f64>,
    marker_poses: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let tcp = rows(&tcp_poses, 6, "tcp_poses")?;
    let marker = rows(&marker_poses, 6, "marker_poses")?;
    if tcp.len() != marker.len() {
        return Err(value_error(format!(
            "{} TCP poses and {} marker poses: give one of each per station",
            tcp.len(),
            marker.len()
        )));
    }
    let samples: Vec<HandEyeSample> = tcp
        .iter()
        .zip(&marker)
        .map(|(t, m)| HandEyeSample {
            tcp_in_base: pose_of(t),
            marker_in_camera: pose_of(m),
        })
        .collect();
    let fit = fit_eye_to_hand(&samples, &HandEyeOptions::default()).map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("camera_in_base", pose_list(&fit.camera_in_base))?;
    out.set_item("marker_in_tcp", pose_list(&fit.marker_in_tcp))?;
    out.set_item("position_residuals", fit.position_residuals)?;
    out.set_item("angle_residuals", fit.angle_residuals)?;
    out.set_item("method", fit.method)?;
    Ok(out)
}
