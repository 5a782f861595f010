//! `fairgrasp._native`: the Rust env, vector env, kinematics and scripted baseline for Python.
//! The gymnasium classes live in the pure-Python package around it (`python/fairgrasp/`);
//! everything here takes and returns NumPy arrays, plain numbers and dicts (infos), and runs the
//! physics with the GIL released. A training recipe's env (`recipe=`) is built here from the
//! recipe's agent and curriculum (fairgrasp-policy), as `fairgrasp train` builds it.
//!
//! ```
//! // The module's action size is the env's.
//! assert_eq!(_native::ACT_DIM, fairgrasp_env::env::spaces::ACT_DIM);
//! ```

use pyo3::prelude::*;

mod agent_env;
mod agent_vec;
mod args;
mod bench;
mod calibrate;
mod chain;
mod compare;
mod curriculum;
mod env;
mod info;
mod kinematics;
mod policy;
mod setup;
#[cfg(feature = "train")]
mod train;
mod vector;

/// The names of the shipped presets, in order.
#[pyfunction]
fn preset_names() -> Vec<&'static str> {
    fairgrasp_env::config::presets::PRESETS
        .iter()
        .map(|(name, _, _)| *name)
        .collect()
}

/// The renamed presets as (old name, current name); the old names are still accepted.
#[pyfunction]
fn renamed_presets() -> Vec<(&'static str, &'static str)> {
    fairgrasp_env::config::presets::RENAMED_PRESETS.to_vec()
}

/// The current name of the preset `name` and, if `name` is a renamed preset's old name, the
/// note saying so (`fairgrasp.presets.current_preset` warns with it); any other name as it is.
#[pyfunction]
fn current_preset_name(name: &str) -> (String, Option<String>) {
    let (current, _) = fairgrasp_env::config::presets::current_name(name);
    (
        current.to_string(),
        fairgrasp_env::config::presets::rename_note(name),
    )
}

/// Values per action (as exported to Python).
pub const ACT_DIM: usize = fairgrasp_env::env::spaces::ACT_DIM;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<env::Env>()?;
    m.add_class::<env::Baseline>()?;
    m.add_class::<vector::VecEnv>()?;
    m.add_function(wrap_pyfunction!(preset_names, m)?)?;
    m.add_function(wrap_pyfunction!(current_preset_name, m)?)?;
    m.add_function(wrap_pyfunction!(renamed_presets, m)?)?;
    m.add_function(wrap_pyfunction!(setup::recipe_names, m)?)?;
    m.add_function(wrap_pyfunction!(setup::recipe_keys, m)?)?;
    m.add_function(wrap_pyfunction!(setup::task_residual_recipe, m)?)?;
    #[cfg(feature = "train")]
    m.add_function(wrap_pyfunction!(train::train, m)?)?;
    m.add("HAS_TRAIN", cfg!(feature = "train"))?;
    m.add_function(wrap_pyfunction!(bench::bench_rust_env, m)?)?;
    m.add_function(wrap_pyfunction!(bench::bench_rust_vec, m)?)?;
    kinematics::register(m)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate_points, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate_hand_eye, m)?)?;
    m.add_class::<policy::NativePolicy>()?;
    m.add_class::<chain::Chain>()?;
    m.add_function(wrap_pyfunction!(policy::scenario_seeds, m)?)?;
    m.add_function(wrap_pyfunction!(policy::wilson_interval, m)?)?;
    m.add_function(wrap_pyfunction!(compare::default_compare_presets, m)?)?;
    m.add_function(wrap_pyfunction!(compare::check_compare, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    m.add("OBS_DIM", fairgrasp_env::env::obs::OBS_DIM)?;
    m.add("ACT_DIM", ACT_DIM)?;
    Ok(())
}
