//! IK for any serial arm from Python: `fairgrasp.kinematics.Chain(urdf, tip)` with `fk(q)` and
//! `ik(pose, start, seed)` ([`fairgrasp_kinematics::chain_ik`]; `fairgrasp fk/ik --urdf` on
//! the CLI). Poses are x y z \[m\] and URDF fixed-axis roll pitch yaw \[rad\] in the chain's root.

use fairgrasp_kinematics::chain_ik::{ChainIk, ChainIkOptions};
use fairgrasp_kinematics::{Pose, UrdfRobot};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;

/// One serial chain of a URDF.
#[pyclass(module = "fairgrasp._native", frozen)]
pub(crate) struct Chain {
    ik: ChainIk,
}

impl Chain {
    /// `values` as the chain's joint vector, or a `ValueError` naming `what`.
    fn joints(&self, values: &PyReadonlyArray1<'_, f64>, what: &str) -> PyResult<Vec<f64>> {
        let q = values.as_slice()?.to_vec();
        if q.len() != self.ik.dof() {
            return Err(value_error(format!(
                "{what} has {} values; the chain to `{}` has {} movable joints ({})",
                q.len(),
                self.ik.chain.tip,
                self.ik.dof(),
                self.ik.names.join(", ")
            )));
        }
        if let Some(i) = q.iter().position(|v| !v.is_finite()) {
            return Err(value_error(format!("{what}[{i}] = {} is not finite", q[i])));
        }
        Ok(q)
    }
}

#[pymethods]
impl Chain {
    #[new]
    #[pyo3(signature = (urdf, tip = None))]
    fn new(urdf: &str, tip: Option<&str>) -> PyResult<Self> {
        let robot = UrdfRobot::from_file(urdf).map_err(value_error)?;
        let ik = ChainIk::new(&robot, tip).map_err(value_error)?;
        Ok(Self { ik })
    }

    /// The movable joints' names, in order.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.ik.names.clone()
    }

    /// Lower and upper limits per joint [rad or m].
    #[getter]
    fn limits<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        (
            self.ik.lower.clone().into_pyarray(py),
            self.ik.upper.clone().into_pyarray(py),
        )
    }

    /// The tip link.
    #[getter]
    fn tip(&self) -> String {
        self.ik.chain.tip.clone()
    }

    /// The tip's pose `[x, y, z, roll, pitch, yaw]` at joints `q`.
    fn fk<'py>(
        &self,
        py: Python<'py>,
        q: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let pose = self.ik.chain.fk(&self.joints(&q, "q")?);
        Ok([pose.xyz(), pose.rpy()].concat().into_pyarray(py))
    }

    /// Joints placing the tip at `pose` from `start` (default: 0 within each joint's limits):
    /// {"joints", "position_error_m", "orientation_error_rad", "iterations", "attempts"}, or
    /// a `ValueError` saying why not (the best residual when it did not converge).
    #[pyo3(signature = (pose, start = None, seed = 0))]
    fn ik<'py>(
        &self,
        py: Python<'py>,
        pose: PyReadonlyArray1<'py, f64>,
        start: Option<PyReadonlyArray1<'py, f64>>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let p = pose.as_slice()?;
        let [x, y, z, r, pi, w]: [f64; 6] = p
            .try_into()
            .map_err(|_| value_error(format!("pose has {} values, expected 6", p.len())))?;
        let target = Pose::try_from_xyz_rpy([x, y, z], [r, pi, w]).map_err(value_error)?;
        let start = match &start {
            Some(s) => self.joints(s, "start")?,
            None => (0..self.ik.dof())
                .map(|i| 0f64.clamp(self.ik.lower[i], self.ik.upper[i]))
                .collect(),
        };
        let options = ChainIkOptions {
            seed,
            ..ChainIkOptions::default()
        };
        let s = py
            .detach(|| self.ik.solve(&target, &start, &options))
            .map_err(value_error)?;
        let d = PyDict::new(py);
        d.set_item("joints", s.joints.into_pyarray(py))?;
        d.set_item("position_error_m", s.position_error_m)?;
        d.set_item("orientation_error_rad", s.orientation_error_rad)?;
        d.set_item("iterations", s.iterations)?;
        d.set_item("attempts", s.attempts)?;
        Ok(d)
    }
}
