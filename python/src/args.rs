//! Python's arguments as Rust values: a Rust error as Python's `ValueError`, a preset (or a
//! whole env config) and an arm simulation as an env config, an action's values checked.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A Rust error as Python's `ValueError` (bad input: config, action, pose), its message
/// bounded as the CLI's are ([`fairgrasp_types::text::bounded_message`]).
pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(fairgrasp_types::text::bounded_message(&e.to_string()))
}

/// Loads a preset by name (or a .toml path), with the arm simulation set.
pub(crate) fn env_config(
    preset: &str,
    arm: &str,
    config_toml: Option<&str>,
) -> PyResult<fairgrasp_env::EnvConfig> {
    let mut config = match config_toml {
        Some(text) => fairgrasp_env::EnvConfig::from_toml_str(text).map_err(value_error)?,
        None => fairgrasp_env::config::presets::load(preset).map_err(value_error)?,
    };
    config.arm.model = arm
        .parse::<fairgrasp_env::ArmSimulation>()
        .map_err(|e| value_error(format!("arm = {arm:?}: {e}")))?;
    Ok(config)
}

/// Checks an action's values: the right count and every value finite; names the index.
pub(crate) fn checked_action(values: &[f64], what: &str) -> PyResult<fairgrasp_env::Action> {
    let dim = fairgrasp_env::env::spaces::ACT_DIM;
    if values.len() != dim {
        return Err(value_error(format!(
            "{what} has {} values, expected {dim}",
            values.len()
        )));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "{what}[{i}] = {} is not finite",
            values[i]
        )));
    }
    let mut a = [0.0; 7];
    a.copy_from_slice(values);
    Ok(fairgrasp_env::Action(a))
}
