//! Trained Rust policies for Python (`fairgrasp.load_policy`): a checkpoint's network run by
//! the burn-free actor of `fairgrasp eval` (the observation normalised with the checkpoint's
//! statistics, the deterministic mean action), and the seeded scenario list `fairgrasp eval`
//! evaluates on, so a Python loop plays exactly its episodes.

use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::checkpoint::{CheckpointMeta, load_actor};
use fairgrasp_policy::shipped::checkpoint_folder;
use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::args::{env_config, value_error};

/// A trained policy: its network and the agent it acts through.
#[pyclass(module = "fairgrasp._native", frozen)]
pub struct NativePolicy {
    meta: CheckpointMeta,
    actor: Actor,
    /// The shipped name or the checkpoint folder it was loaded from.
    #[pyo3(get)]
    source: String,
}

#[pymethods]
impl NativePolicy {
    #[new]
    fn new(name_or_folder: &str) -> PyResult<Self> {
        let dir = checkpoint_folder(name_or_folder).map_err(value_error)?;
        let (meta, actor) = load_actor(&dir).map_err(value_error)?;
        Ok(Self {
            meta,
            actor,
            source: name_or_folder.to_string(),
        })
    }

    /// The agent the network acts through (`mode`, `action_space`, `gripper`,
    /// `residual_scale`) as JSON: the recipe env's `agent` override.
    fn agent_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.meta.agent).map_err(value_error)
    }

    /// The network's input size (the recipe env's observation size).
    #[getter]
    fn input_dim(&self) -> usize {
        self.meta.input_dim
    }

    /// Environment steps it was trained for.
    #[getter]
    fn trained_timesteps(&self) -> u64 {
        self.meta.timesteps
    }

    /// The deterministic actions of a batch of policy inputs `[n, input_dim]` (float32):
    /// `[n, 7]`. A wrong width or a non-finite input is refused naming the row and column.
    fn predict_batch<'py>(
        &self,
        py: Python<'py>,
        inputs: PyReadonlyArray2<'py, f32>,
    ) -> PyResult<Bound<'py, PyArray2<f32>>> {
        let shape = inputs.shape();
        let (rows, width) = (shape[0], shape[1]);
        if width != self.meta.input_dim {
            return Err(value_error(format!(
                "the observation has {width} values, this policy takes {} (make its env with policy.make_env(preset))",
                self.meta.input_dim
            )));
        }
        let flat = inputs.to_vec().map_err(value_error)?;
        if let Some(i) = flat.iter().position(|v| !v.is_finite()) {
            return Err(value_error(format!(
                "observation[{}][{}] = {} is not finite",
                i / width,
                i % width,
                flat[i]
            )));
        }
        let mut out = Vec::with_capacity(rows * self.meta.act_dim);
        for row in flat.chunks_exact(width.max(1)) {
            out.extend(self.actor.mean(&self.meta.obs_norm.normalize(row)));
        }
        numpy::PyArray1::from_vec(py, out).reshape([rows, self.meta.act_dim])
    }
}

/// The scenario seeds `fairgrasp eval --preset P --episodes N --seed S` plays, in order (the
/// env's `reset(seed=…)` with each one plays the same scenario).
#[pyfunction]
#[pyo3(signature = (preset, seed, episodes, arm = "servo"))]
pub(crate) fn scenario_seeds(
    preset: &str,
    seed: u64,
    episodes: usize,
    arm: &str,
) -> PyResult<Vec<u64>> {
    if !(1..=1_000_000).contains(&episodes) {
        return Err(value_error(format!(
            "episodes = {episodes}: must be in 1..=1000000"
        )));
    }
    let config = env_config(preset, arm, None)?;
    let set =
        fairgrasp_env::scenario::scenario_set(&config, seed, episodes).map_err(value_error)?;
    Ok(set.iter().map(|s| s.seed).collect())
}

/// The 95 % Wilson interval of `successes` in `n` episodes (the same as every report's).
#[pyfunction]
pub(crate) fn wilson_interval(successes: usize, n: usize) -> PyResult<(f64, f64)> {
    if successes > n {
        return Err(value_error(format!(
            "successes = {successes} exceeds n = {n}"
        )));
    }
    Ok(fairgrasp_types::wilson_interval(successes, n))
}
