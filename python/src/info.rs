//! A step's info as Python objects, built here rather than parsed from JSON text: the few values
//! every step has as plain numbers, and the scenario and the episode record (at a reset and at
//! an episode's end only) as dicts converted from their serde form.
//!
//! The env's episode record is `info["episode_record"]`, not `info["episode"]`: gymnasium's
//! `RecordEpisodeStatistics` and Stable-Baselines3's `Monitor` own that key (they write
//! `{"r", "l", "t"}` there and refuse an info that has it already).

use fairgrasp_env::Info;
use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde::Serialize;

use crate::args::value_error;

/// A serde value as the Python object `json.loads` would give for its JSON.
pub(crate) fn json_to_py<'py>(
    py: Python<'py>,
    value: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    use serde_json::Value;
    match value {
        Value::Null => Ok(py.None().into_bound(py)),
        Value::Bool(b) => b.into_bound_py_any(py),
        Value::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
            (Some(u), _, _) => u.into_bound_py_any(py),
            (None, Some(i), _) => i.into_bound_py_any(py),
            (None, None, f) => f.unwrap_or(f64::NAN).into_bound_py_any(py),
        },
        Value::String(s) => s.into_bound_py_any(py),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(json_to_py(py, item)?)?;
            }
            Ok(list.into_any())
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (k, v) in map {
                dict.set_item(k, json_to_py(py, v)?)?;
            }
            Ok(dict.into_any())
        }
    }
}

/// Any serializable value as a Python object (see [`json_to_py`]).
pub(crate) fn to_py<'py, T: Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value).map_err(value_error)?;
    json_to_py(py, &v)
}

/// The curriculum's stage: index and name.
pub(crate) type Stage = (usize, String);

/// One env's info: `step`, `success`, `simulated`, `scenario_seed`, `failure`,
/// `collision_depth_m`, `physics_fault`, the curriculum's stage (`curriculum_stage`,
/// `curriculum_stage_name`) when there is one; with `whole` (a reset, an episode's end) also
/// `scenario`; at an episode's end `episode_record` (the env's record, with the policy's
/// verdict), `outcome` and `collision_pair` (None while the episode runs).
pub(crate) fn info_dict<'py>(
    py: Python<'py>,
    info: &Info,
    stage: Option<&Stage>,
    whole: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("step", info.step)?;
    d.set_item("success", info.success)?;
    d.set_item("simulated", info.simulated)?;
    d.set_item("scenario_seed", info.scenario.map(|s| s.seed))?;
    match &info.failure {
        Some(f) => d.set_item("failure", to_py(py, f)?)?,
        None => d.set_item("failure", py.None())?,
    }
    d.set_item("collision_depth_m", info.collision_depth_m)?;
    d.set_item("physics_fault", info.physics_fault.as_deref())?;
    if let Some((index, name)) = stage {
        d.set_item("curriculum_stage", *index)?;
        d.set_item("curriculum_stage_name", name)?;
    }
    if whole && let Some(s) = &info.scenario {
        d.set_item("scenario", to_py(py, s)?)?;
    }
    match &info.episode {
        Some(record) => {
            d.set_item("episode_record", to_py(py, record)?)?;
            d.set_item("outcome", to_py(py, &record.outcome)?)?;
            match &record.collision_pair {
                Some([a, b]) => d.set_item("collision_pair", (a, b))?,
                None => d.set_item("collision_pair", py.None())?,
            }
        }
        None => {
            d.set_item("outcome", py.None())?;
            d.set_item("collision_pair", py.None())?;
        }
    }
    Ok(d)
}
