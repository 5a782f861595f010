//! `VecEnv`: N envs (of a preset, or of a training recipe with its agent and one shared
//! curriculum) stepped on Rust threads in one call with the GIL released, auto-resetting in the
//! step that ends an episode (gymnasium's `SAME_STEP` mode). Infos come back as NumPy arrays
//! built here (one value per env), plus, for the envs whose episode ended, their last
//! observation and last info.

use std::sync::Mutex;

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::agent_vec::AgentVecEnv;
use crate::args::value_error;
use crate::env::action7;
use crate::info::info_dict;
use crate::setup::Setup;

/// What `step` returns: obs [n, dim], rewards [n], terminated [n], truncated [n], the infos as
/// arrays, and the ended episodes as a list of (env index, last observation, last info).
type VecStepTuple<'py> = (
    Bound<'py, PyArray2<f32>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyDict>,
    Bound<'py, PyList>,
);

/// N grasping envs on `threads` Rust threads; episode k of env i starts from scenario seed
/// `seed + i · 1 000 000 + k`, reported in `info["scenario_seed"]`.
#[pyclass(module = "fairgrasp._native")]
pub struct VecEnv {
    inner: Mutex<AgentVecEnv>,
    setup: Setup,
    n: usize,
}

/// The per-env arrays of the last batch: `success`, `step`, `simulated`, `scenario_seed` (the
/// episode each env is in now) and `curriculum_stage`. An env that auto-reset reports its new
/// episode (not successful, step 0, not simulated).
fn info_arrays<'py>(py: Python<'py>, env: &AgentVecEnv) -> PyResult<Bound<'py, PyDict>> {
    let batch = env.batch();
    let n = env.len();
    let reset = |e: usize| batch.terminated[e] || batch.truncated[e];
    let d = PyDict::new(py);
    let success: Vec<bool> = (0..n)
        .map(|e| !reset(e) && batch.infos[e].success)
        .collect();
    let step: Vec<i64> = (0..n)
        .map(|e| {
            if reset(e) {
                0
            } else {
                batch.infos[e].step as i64
            }
        })
        .collect();
    let simulated: Vec<bool> = (0..n)
        .map(|e| !reset(e) && batch.infos[e].simulated)
        .collect();
    d.set_item("success", PyArray1::from_vec(py, success))?;
    d.set_item("step", PyArray1::from_vec(py, step))?;
    d.set_item("simulated", PyArray1::from_vec(py, simulated))?;
    d.set_item("scenario_seed", PyArray1::from_slice(py, &batch.seeds))?;
    if let Some((stage, _)) = env.stage() {
        d.set_item(
            "curriculum_stage",
            PyArray1::from_vec(py, vec![stage as i64; n]),
        )?;
    }
    Ok(d)
}

fn obs_rows<'py>(py: Python<'py>, env: &AgentVecEnv) -> PyResult<Bound<'py, PyArray2<f32>>> {
    PyArray1::from_slice(py, env.obs()).reshape([env.len(), env.dim()])
}

#[pymethods]
impl VecEnv {
    /// `n` envs of `preset` (or `config_toml`), or of `recipe` with `overrides_json` (see
    /// `Env`), on `threads` threads.
    #[new]
    #[pyo3(signature = (n, preset = "full", arm = "servo", threads = 2, seed = 0, config_toml = None, recipe = None, overrides_json = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        n: usize,
        preset: &str,
        arm: &str,
        threads: usize,
        seed: u64,
        config_toml: Option<&str>,
        recipe: Option<&str>,
        overrides_json: Option<&str>,
    ) -> PyResult<Self> {
        if !(1..=4096).contains(&n) || !(1..=256).contains(&threads) {
            return Err(value_error(format!(
                "n = {n}, threads = {threads}: n must be in 1..=4096 and threads in 1..=256"
            )));
        }
        let setup = Setup::new(preset, arm, config_toml, recipe, overrides_json)?;
        let inner = AgentVecEnv::new(&setup, n, threads, seed).map_err(value_error)?;
        Ok(Self {
            inner: Mutex::new(inner),
            setup,
            n,
        })
    }

    /// Number of envs.
    #[getter]
    fn num_envs(&self) -> usize {
        self.n
    }

    /// Starts every env's next episode: (obs [n, dim], infos as arrays).
    fn reset<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyArray2<f32>>, Bound<'py, PyDict>)> {
        let mut guard = self.inner.lock().map_err(value_error)?;
        let inner: &mut AgentVecEnv = &mut guard;
        py.detach(|| inner.reset()).map_err(value_error)?;
        Ok((obs_rows(py, inner)?, info_arrays(py, inner)?))
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
            .map(|(i, row)| action7(row, &format!("actions[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        let mut guard = self.inner.lock().map_err(value_error)?;
        let inner: &mut AgentVecEnv = &mut guard;
        py.detach(|| inner.step(&actions)).map_err(value_error)?;
        let stage = inner.stage();
        let ended = PyList::empty(py);
        for (e, last, info) in inner.ended() {
            let info = info_dict(py, info, stage.as_ref(), true)?;
            ended.append((*e, PyArray1::from_slice(py, last), info))?;
        }
        let batch = inner.batch();
        Ok((
            obs_rows(py, inner)?,
            PyArray1::from_slice(py, &batch.rewards),
            PyArray1::from_slice(py, &batch.terminated),
            PyArray1::from_slice(py, &batch.truncated),
            info_arrays(py, inner)?,
            ended,
        ))
    }

    /// The observation space as JSON (see `Env.observation_space_json`).
    fn observation_space_json(&self) -> PyResult<String> {
        self.setup.space_json(self.setup.observation_space())
    }

    /// The action space as JSON (see `Env.action_space_json`).
    fn action_space_json(&self) -> PyResult<String> {
        self.setup.space_json(self.setup.action_space())
    }

    /// The shared curriculum's stage (index, name); None without a curriculum.
    fn curriculum_stage(&self) -> PyResult<Option<(usize, String)>> {
        Ok(self.inner.lock().map_err(value_error)?.stage())
    }

    /// Moves the shared curriculum to `stage` (clamped to the last), from each env's next
    /// reset on.
    fn set_curriculum_stage(&self, stage: usize) -> PyResult<()> {
        let mut env = self.inner.lock().map_err(value_error)?;
        env.set_stage(stage).map_err(value_error)
    }
}
