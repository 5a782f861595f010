//! The Rust side of `scripts/python-bench.py`: the same env steps as the Python loop, timed in a
//! Rust loop in this process (the peer a Python env's per-step cost is a ratio against).

use std::time::Instant;

use fairgrasp_env::vec::VecEnv;
use fairgrasp_env::{Action, TaskEnv};
use numpy::{PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::args::{env_config, value_error};

/// Steps one `TaskEnv` of `preset` through `actions` [steps, 7] in a Rust loop (GIL released),
/// resetting to seeds `seed`, `seed + 1`, ... as episodes end: (wall seconds of the loop, share
/// of the steps that ran rigid-body physics).
#[pyfunction]
pub(crate) fn bench_rust_env(
    py: Python<'_>,
    preset: &str,
    actions: PyReadonlyArray2<'_, f64>,
    seed: u64,
) -> PyResult<(f64, f64)> {
    if actions.shape()[1] != 7 {
        return Err(value_error("actions must have shape [steps, 7]"));
    }
    let actions: Vec<Action> = actions
        .as_slice()?
        .chunks(7)
        .map(|c| Action(c.try_into().unwrap_or([0.0; 7])))
        .collect();
    let mut env = TaskEnv::new(env_config(preset, "servo", None)?).map_err(value_error)?;
    py.detach(|| -> Result<(f64, f64), fairgrasp_env::EnvError> {
        let mut next = seed;
        env.reset(next)?;
        let (mut simulated, start) = (0usize, Instant::now());
        for a in &actions {
            let step = env.step(a)?;
            simulated += usize::from(step.info.simulated);
            if step.terminated || step.truncated {
                next += 1;
                env.reset(next)?;
            }
        }
        let wall = start.elapsed().as_secs_f64();
        Ok((wall, simulated as f64 / actions.len().max(1) as f64))
    })
    .map_err(value_error)
}

/// Steps a Rust `VecEnv` of `n` envs of `preset` on `threads` threads through `actions`
/// [batches, n, 7] (GIL released): wall seconds of the loop.
#[pyfunction]
pub(crate) fn bench_rust_vec(
    py: Python<'_>,
    preset: &str,
    threads: usize,
    actions: PyReadonlyArray3<'_, f64>,
    seed: u64,
) -> PyResult<f64> {
    let shape = actions.shape().to_vec();
    if shape[2] != 7 || shape[1] == 0 {
        return Err(value_error("actions must have shape [batches, n, 7]"));
    }
    let batches: Vec<Vec<Action>> = actions
        .as_slice()?
        .chunks(shape[1] * 7)
        .map(|b| {
            b.chunks(7)
                .map(|c| Action(c.try_into().unwrap_or([0.0; 7])))
                .collect()
        })
        .collect();
    let config = env_config(preset, "servo", None)?;
    let mut env = VecEnv::new(&config, shape[1], threads, seed).map_err(value_error)?;
    py.detach(|| -> Result<f64, fairgrasp_env::EnvError> {
        env.reset()?;
        let start = Instant::now();
        for b in &batches {
            env.step(b)?;
        }
        Ok(start.elapsed().as_secs_f64())
    })
    .map_err(value_error)
}
