//! `VecEnv`: N envs stepped on Rust threads in one call, auto-resetting in the step that ends an
//! episode (gymnasium's `SAME_STEP` mode; the ended episode's last observation comes separately).

use std::sync::Mutex;

use fairgrasp_env::env::obs::OBS_DIM;
use fairgrasp_env::vec;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::{checked_action, env_config, value_error};

/// What `step` returns: obs [n, 23], rewards [n], terminated [n], truncated [n], final
/// observations [n, 23] (NaN rows where no episode ended), and the infos as JSON.
type VecStepTuple<'py> = (
    Bound<'py, PyArray2<f32>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray2<f32>>,
    Vec<String>,
);

/// N grasping envs on `threads` Rust threads; episode k of env i starts from a scenario seed
/// derived from (`seed`, i, k), reported in each info's `scenario.seed`.
#[pyclass(module = "fairgrasp._native")]
pub struct VecEnv {
    inner: Mutex<vec::VecEnv>,
    n: usize,
}

fn rows<'py>(py: Python<'py>, rows: Vec<Vec<f32>>) -> PyResult<Bound<'py, PyArray2<f32>>> {
    let n = rows.len();
    let flat: Vec<f32> = rows.into_iter().flatten().collect();
    flat.into_pyarray(py).reshape([n, OBS_DIM])
}

/// Each env's info as JSON (parsed on the Python side).
fn infos_json(infos: &[fairgrasp_env::Info]) -> PyResult<Vec<String>> {
    infos
        .iter()
        .map(|i| serde_json::to_string(i).map_err(value_error))
        .collect()
}

#[pymethods]
impl VecEnv {
    #[new]
    #[pyo3(signature = (n, preset = "full", arm = "servo", threads = 2, seed = 0, config_toml = None))]
    fn new(
        n: usize,
        preset: &str,
        arm: &str,
        threads: usize,
        seed: u64,
        config_toml: Option<&str>,
    ) -> PyResult<Self> {
        if !(1..=4096).contains(&n) || !(1..=256).contains(&threads) {
            return Err(value_error(format!(
                "n = {n}, threads = {threads}: n must be in 1..=4096 and threads in 1..=256"
            )));
        }
        let config = env_config(preset, arm, config_toml)?;
        let inner = vec::VecEnv::new(&config, n, threads, seed).map_err(value_error)?;
        Ok(Self {
            inner: Mutex::new(inner),
            n,
        })
    }

    /// Number of envs.
    #[getter]
    fn num_envs(&self) -> usize {
        self.n
    }

    /// Starts every env's next episode: (obs [n, 23], infos JSON).
    fn reset<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyArray2<f32>>, Vec<String>)> {
        let mut guard = self.inner.lock().map_err(value_error)?;
        let inner: &mut vec::VecEnv = &mut guard;
        let out = py
            .detach(|| {
                inner.reset()?;
                Ok::<_, fairgrasp_env::EnvError>(inner.batch().clone())
            })
            .map_err(value_error)?;
        let obs = out.obs.iter().map(crate::env::obs_array).collect();
        let infos = infos_json(&out.infos)?;
        Ok((rows(py, obs)?, infos))
    }

    /// Steps every env with its row of `actions` [n, 7] (physics on the Rust threads, GIL
    /// released). A wrong shape or a non-finite value raises `ValueError` naming env and index.
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<VecStepTuple<'py>> {
        let shape = actions.shape();
        if shape != [self.n, 7] {
            return Err(value_error(format!(
                "actions have shape {shape:?}, expected [{}, 7]",
                self.n
            )));
        }
        let values = actions.as_slice()?;
        let actions = values
            .chunks(7)
            .enumerate()
            .map(|(i, row)| checked_action(row, &format!("actions[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        let mut guard = self.inner.lock().map_err(value_error)?;
        let inner: &mut vec::VecEnv = &mut guard;
        let out = py
            .detach(|| inner.step(&actions).cloned())
            .map_err(value_error)?;
        let obs = out.obs.iter().map(crate::env::obs_array).collect();
        let final_obs = out
            .final_obs
            .iter()
            .map(|o| {
                o.as_ref()
                    .map_or(vec![f32::NAN; OBS_DIM], crate::env::obs_array)
            })
            .collect();
        let infos = infos_json(&out.infos)?;
        Ok((
            rows(py, obs)?,
            out.rewards.clone().into_pyarray(py),
            out.terminated.clone().into_pyarray(py),
            out.truncated.clone().into_pyarray(py),
            rows(py, final_obs)?,
            infos,
        ))
    }
}
