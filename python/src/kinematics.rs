//! The FR3/FR5 kinematics for Python, NumPy in and out: `fk`, `ik` (every closed-form branch),
//! `ik_qp` (the clarabel QP solver) and `world_to_base`. Poses are x y z \[m\] and URDF fixed-axis
//! roll pitch yaw \[rad\] in base_link, as on the CLI (`fairgrasp fk/ik --json` give the same).

use fairgrasp_kinematics::{AnalyticIkOptions, ArmKind, ArmModel, EndFrame, Pose, QpIkOptions};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

fn model(name: &str) -> PyResult<ArmModel> {
    ArmKind::ALL
        .into_iter()
        .find(|k| k.name() == name)
        .map(ArmKind::model)
        .ok_or_else(|| value_error(format!("model = {name:?}: choose \"fr3\" or \"fr5\"")))
}

fn frame(name: &str) -> PyResult<EndFrame> {
    match name {
        "tool0" | "flange" => Ok(EndFrame::Flange),
        "tcp" => Ok(EndFrame::Tcp),
        other => Err(value_error(format!(
            "frame = {other:?}: choose \"tool0\" or \"tcp\""
        ))),
    }
}

/// `N` finite values from an array, or a `ValueError` naming `what` and the index.
fn finite<const N: usize>(array: &PyReadonlyArray1<'_, f64>, what: &str) -> PyResult<[f64; N]> {
    let values = array.as_slice()?;
    let out: [f64; N] = values
        .try_into()
        .map_err(|_| value_error(format!("{what} has {} values, expected {N}", values.len())))?;
    if let Some(i) = out.iter().position(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "{what}[{i}] = {} is not finite",
            out[i]
        )));
    }
    Ok(out)
}

fn pose_dict<'py>(py: Python<'py>, pose: &Pose) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("xyz", pose.xyz().to_vec().into_pyarray(py))?;
    d.set_item("rpy", pose.rpy().to_vec().into_pyarray(py))?;
    let m = pose.iso.to_homogeneous();
    let rows: Vec<f64> = (0..4)
        .flat_map(|r| (0..4).map(move |c| m[(r, c)]))
        .collect();
    let matrix: Bound<'py, PyArray2<f64>> = rows.into_pyarray(py).reshape([4, 4])?;
    d.set_item("matrix", matrix)?;
    Ok(d)
}

/// Forward kinematics: {"flange": {...}, "tcp": {...}}, each with "xyz", "rpy" and the 4×4
/// "matrix" of the frame in base_link.
#[pyfunction]
#[pyo3(signature = (joints, model_name = "fr3"))]
fn fk<'py>(
    py: Python<'py>,
    joints: PyReadonlyArray1<'py, f64>,
    model_name: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let m = model(model_name)?;
    let q = finite::<6>(&joints, "joints")?;
    let d = PyDict::new(py);
    d.set_item("flange", pose_dict(py, &m.fk_flange(&q))?)?;
    d.set_item("tcp", pose_dict(py, &m.fk_tcp(&q))?)?;
    d.set_item("in_limits", m.in_limits(&q, 0.0))?;
    Ok(d)
}

/// Every closed-form IK branch placing `frame` at `pose` (x y z roll pitch yaw): a list of
/// {"joints", "in_limits", "branch"}; empty if the pose is out of reach. `current` picks θ6 at a
/// wrist singularity (as `fairgrasp ik --current`).
#[pyfunction]
#[pyo3(signature = (pose, frame_name = "tool0", current = None, model_name = "fr3"))]
fn ik<'py>(
    py: Python<'py>,
    pose: PyReadonlyArray1<'py, f64>,
    frame_name: &str,
    current: Option<PyReadonlyArray1<'py, f64>>,
    model_name: &str,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let m = model(model_name)?;
    let p = finite::<6>(&pose, "pose")?;
    let current = match &current {
        Some(c) => finite::<6>(c, "current")?,
        None => [0.0; 6],
    };
    let target = Pose::from_xyz_rpy([p[0], p[1], p[2]], [p[3], p[4], p[5]]);
    let options = AnalyticIkOptions {
        wrist_singular_q6: current[5],
        ..Default::default()
    };
    let solutions = m
        .ik_analytic(&target, frame(frame_name)?, &options)
        .unwrap_or_default();
    solutions
        .iter()
        .map(|s| {
            let d = PyDict::new(py);
            d.set_item("joints", s.joints.to_vec().into_pyarray(py))?;
            d.set_item("in_limits", s.in_limits)?;
            d.set_item("branch", s.branch)?;
            Ok(d)
        })
        .collect()
}

/// The clarabel QP IK from `start` (joint limits respected; tolerance 1e-4 m / 1e-3 rad): the
/// joints, or `ValueError` saying why it failed.
#[pyfunction]
#[pyo3(signature = (pose, start, frame_name = "tool0", seed = 0, model_name = "fr3"))]
fn ik_qp<'py>(
    py: Python<'py>,
    pose: PyReadonlyArray1<'py, f64>,
    start: PyReadonlyArray1<'py, f64>,
    frame_name: &str,
    seed: u64,
    model_name: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let m = model(model_name)?;
    let p = finite::<6>(&pose, "pose")?;
    let q0 = finite::<6>(&start, "start")?;
    let target = Pose::from_xyz_rpy([p[0], p[1], p[2]], [p[3], p[4], p[5]]);
    let options = QpIkOptions {
        frame: frame(frame_name)?,
        seed,
        ..Default::default()
    };
    let solution = py
        .detach(|| m.ik_qp(&target, &q0, &options))
        .map_err(value_error)?;
    Ok(solution.joints.to_vec().into_pyarray(py))
}

/// A world point [m] in base_link, given base_link's pose in the world (x y z roll pitch yaw).
#[pyfunction]
fn world_to_base<'py>(
    py: Python<'py>,
    base_pose: PyReadonlyArray1<'py, f64>,
    point: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let b = finite::<6>(&base_pose, "base_pose")?;
    let p = finite::<3>(&point, "point")?;
    let base = Pose::from_xyz_rpy([b[0], b[1], b[2]], [b[3], b[4], b[5]]);
    Ok(fairgrasp_kinematics::world_to_base(&base, p)
        .to_vec()
        .into_pyarray(py))
}

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fk, m)?)?;
    m.add_function(wrap_pyfunction!(ik, m)?)?;
    m.add_function(wrap_pyfunction!(ik_qp, m)?)?;
    m.add_function(wrap_pyfunction!(world_to_base, m)?)?;
    Ok(())
}
