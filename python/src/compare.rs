//! `fairgrasp.compare` from Python: the comparison of `fairgrasp compare` (the scripts and the
//! shipped policies on the same seeded scenarios) with methods evaluated in Python beside them,
//! written as the same report folder, whole or not at all.

use std::path::Path;

use fairgrasp_evaluate::compare::{
    ComparePreset, CompareSpec, DEFAULT_PRESETS, DEFAULT_REPLAY_EPISODES, LearnedPolicy,
    default_threads, run_comparison,
};
use fairgrasp_policy::shipped;
use fairgrasp_report::comparison_folder::write_comparison_folder;
use fairgrasp_report::{Existing, StagedFolder};
use fairgrasp_types::EpisodeRecord;
use pyo3::prelude::*;
use serde::Deserialize;

use crate::args::{env_config, value_error};

/// The presets `fairgrasp compare` uses without `--preset`.
#[pyfunction]
pub(crate) fn default_compare_presets() -> Vec<&'static str> {
    DEFAULT_PRESETS.to_vec()
}

/// The comparison asked for: presets (their configs), scenarios, seed, threads.
fn spec(
    presets: &[String],
    episodes: usize,
    seed: u64,
    arm: &str,
    threads: Option<usize>,
    command: &str,
) -> PyResult<CompareSpec> {
    let presets = presets
        .iter()
        .map(|p| {
            Ok(ComparePreset {
                name: p.clone(),
                config: env_config(p, arm, None)?,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let threads = threads.unwrap_or_else(default_threads);
    let spec = CompareSpec {
        presets,
        episodes,
        seed,
        threads,
        episode: None,
        replay_episodes: DEFAULT_REPLAY_EPISODES.min(episodes),
        command: command.to_string(),
    };
    spec.check().map_err(value_error)?;
    Ok(spec)
}

/// Checks a comparison request and its output folder before any episode runs (the Python
/// methods are evaluated between this check and [`compare`]).
#[pyfunction]
#[pyo3(signature = (presets, episodes, seed, out, force = false, arm = "servo", threads = None))]
pub(crate) fn check_compare(
    presets: Vec<String>,
    episodes: usize,
    seed: u64,
    out: &str,
    force: bool,
    arm: &str,
    threads: Option<usize>,
) -> PyResult<()> {
    spec(&presets, episodes, seed, arm, threads, "")?;
    // Created and dropped: the folder is writable and replaceable (the staging folder goes).
    StagedFolder::create(
        Path::new(out),
        Existing::from_force(force),
        "fairgrasp.compare",
    )
    .map(drop)
    .map_err(value_error)
}

/// One method evaluated in Python: its name, where it came from, and its episode records per
/// preset (`fairgrasp.evaluate`'s `records`).
#[derive(Deserialize)]
struct PythonMethod {
    name: String,
    policy: String,
    results: Vec<(String, Vec<EpisodeRecord>)>,
}

/// Runs the comparison (the scripts, and the shipped policies when `shipped`), adds the Python
/// methods (`methods_json`: a list of [`PythonMethod`]) and writes the report folder `out`, as
/// `fairgrasp compare --out OUT` writes it; returns the files written. The GIL is released
/// while episodes run.
#[pyfunction]
#[pyo3(signature = (presets, episodes, seed, out, methods_json, force = false, arm = "servo", threads = None, shipped = true, command = "fairgrasp.compare"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn compare(
    py: Python<'_>,
    presets: Vec<String>,
    episodes: usize,
    seed: u64,
    out: &str,
    methods_json: &str,
    force: bool,
    arm: &str,
    threads: Option<usize>,
    shipped: bool,
    command: &str,
) -> PyResult<Vec<String>> {
    let spec = spec(&presets, episodes, seed, arm, threads, command)?;
    let methods: Vec<PythonMethod> = serde_json::from_str(methods_json).map_err(value_error)?;
    let out = Path::new(out);
    py.detach(|| -> Result<Vec<String>, String> {
        let learned = if shipped {
            let dirs = shipped::default_compare_policies().map_err(|e| e.to_string())?;
            LearnedPolicy::load_all(&dirs).map_err(|e| e.to_string())?
        } else {
            Vec::new()
        };
        let staged = StagedFolder::create(out, Existing::from_force(force), "fairgrasp.compare")
            .map_err(|e| e.to_string())?;
        let mut output = run_comparison(&spec, &learned, &|_| {}).map_err(|e| e.to_string())?;
        for m in methods {
            output
                .comparison
                .add_method(&m.name, &m.policy, m.results)
                .map_err(|e| e.to_string())?;
        }
        let comparison = output.comparison.clone();
        write_comparison_folder(staged, &comparison, out, spec.threads, |dir| {
            output.save_episodes(dir).map_err(|e| e.to_string())
        })
        .map_err(|e| e.to_string())
    })
    .map_err(value_error)
}
