//! `train`: the Rust PPO trainer (`fairgrasp train`) from Python, with the GIL released while it
//! runs: the same config, the same run folder (`config.toml`, `metrics.csv`, `checkpoints/`,
//! `eval.json`), progress handed to a Python callback after every update. Needs the crate's
//! `train` feature (it links fairgrasp-rl, and so burn).

use std::path::Path;

use fairgrasp_policy::recipe::overlay;
use fairgrasp_policy::recipes;
use fairgrasp_rl::run::resume::{self, ResumeOptions};
use fairgrasp_rl::run::train::{Progress, TrainConfig, train_with};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::value_error;
use crate::info::to_py;

/// The training config of `config` (a shipped recipe's name or a training config's path) with
/// `overrides` (JSON: any of the config's keys; tables merge key by key) laid over it, checked
/// as `fairgrasp train` checks a file; for a resume of the run in `resuming`, a preset file is
/// the run's copy of it (as the CLI takes it).
fn train_config(
    config: &str,
    overrides_json: Option<&str>,
    resuming: Option<&Path>,
) -> PyResult<TrainConfig> {
    let (text, what) = recipes::text(config).map_err(value_error)?;
    let mut table: toml::Table =
        toml::from_str(&text).map_err(|e| value_error(format!("{what}: {e}")))?;
    if let Some(json) = overrides_json {
        let overrides: toml::Table = serde_json::from_str(json)
            .map_err(|e| value_error(format!("overrides: {e} (None is not a value here)")))?;
        overlay(&mut table, &overrides);
    }
    let mut config: TrainConfig = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| value_error(format!("{what} with the overrides: {e}")))?;
    if let Some(dir) = resuming {
        config.env_snapshot = fairgrasp_rl::run::snapshot::env_snapshot_of(&config.preset, dir);
    }
    config
        .validate()
        .map_err(|e| value_error(format!("{what} with the overrides: {e}")))?;
    Ok(config)
}

/// One update's progress as a dict: `timesteps`, `total`, `stage` (the curriculum's), `eval`
/// (the evaluation's success rate when one ran, else None), `episodes`, `success` (share of the
/// update's episodes) and `mean_return`.
fn progress_dict<'py>(py: Python<'py>, p: &Progress) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let episodes = &p.stats.episodes;
    let n = episodes.len().max(1) as f64;
    d.set_item("timesteps", p.timesteps)?;
    d.set_item("total", p.total)?;
    d.set_item("stage", p.stage)?;
    d.set_item("eval", p.eval)?;
    d.set_item("episodes", episodes.len())?;
    d.set_item(
        "success",
        episodes.iter().filter(|e| e.success).count() as f64 / n,
    )?;
    d.set_item(
        "mean_return",
        episodes
            .iter()
            .map(|e| e.episode_return as f64)
            .sum::<f64>()
            / n,
    )?;
    Ok(d)
}

/// Trains (or with `resume`, continues) in `run_dir` as `fairgrasp train --config CONFIG
/// --run-dir RUN_DIR [--resume]` does, with the GIL released; `progress(dict)` is called after
/// every update (with the GIL). Returns the final evaluation (`eval.json`'s report) as a dict.
/// An exception in `progress` stops nothing: it is raised when the run has ended.
#[pyfunction]
#[pyo3(signature = (config, run_dir, overrides_json = None, resume = false, progress = None, force = false))]
pub(crate) fn train<'py>(
    py: Python<'py>,
    config: &str,
    run_dir: &str,
    overrides_json: Option<&str>,
    resume: bool,
    progress: Option<Py<PyAny>>,
    force: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let run_dir = Path::new(run_dir);
    let mut config = train_config(config, overrides_json, resume.then_some(run_dir))?;
    let seed_given = overrides_json
        .and_then(|j| serde_json::from_str::<serde_json::Value>(j).ok())
        .is_some_and(|v| v.get("seed").is_some());
    if resume && !seed_given {
        config.seed = resume::run_seed(run_dir, config.seed).map_err(value_error)?;
    }
    let options = ResumeOptions {
        resume,
        accept_config_changes: false,
        force,
    };
    let mut callback_error: Option<PyErr> = None;
    let report = py
        .detach(|| {
            train_with(&config, run_dir, options, &mut |p| {
                let Some(cb) = &progress else { return };
                if callback_error.is_some() {
                    return;
                }
                Python::attach(|py| {
                    let result = progress_dict(py, &p).and_then(|d| cb.call1(py, (d,)));
                    if let Err(e) = result {
                        callback_error = Some(e);
                    }
                });
            })
        })
        .map_err(value_error)?;
    if let Some(e) = callback_error {
        return Err(e);
    }
    to_py(py, &report)
}
