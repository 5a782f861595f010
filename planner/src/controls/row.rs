//! One row of the table of controls ([`Control`]) and what rows share: a control without
//! tunable parameters (`no_values`, `set_nothing`) and one `compare` always runs (`always`).
//! Each task's rows live in its folder and import this; the table ([`crate::controls`])
//! imports the rows (a row file never imports the table back).

use fairgrasp_env::episode::Policy;
use fairgrasp_env::{EnvConfig, TaskKind};

use crate::controls::params::{Param, ParamValues};
use crate::lift::calibrated::CameraCalibration;

/// One hand-written control. Its parameters live in the env's config (one table per control,
/// [`Control::table`]), so that a tuned setting is a preset fragment and every command that
/// reads a preset runs the control as tuned. `Copy`: the table is assembled from the tasks'
/// rows at compile time.
#[derive(Clone, Copy)]
pub struct Control {
    /// Its name on the command line (`baseline --script`, `tune --control`, `replay --policy`).
    pub cli: &'static str,
    /// Its name in a comparison and the report.
    pub report: &'static str,
    /// The task it runs.
    pub task: TaskKind,
    /// What `tune` may set.
    pub params: &'static [Param],
    /// The preset table its parameters live in (`task.place.search`); `None` without any.
    pub table: Option<&'static str>,
    /// Its parameters' values in an env.
    pub values: fn(&EnvConfig) -> ParamValues,
    /// Sets `values` (names of `params`) in an env's config; `EnvConfig::validate` checks them.
    pub set: fn(&mut EnvConfig, &ParamValues),
    /// The control for an env, the cell's camera calibration at hand.
    pub build: fn(&EnvConfig, &CameraCalibration) -> Box<dyn Policy>,
    /// Does `compare` run it on presets like this env's by default?
    pub in_compare: fn(&EnvConfig) -> bool,
}

impl Control {
    /// The parameter called `name`.
    pub fn param(&self, name: &str) -> Option<&'static Param> {
        self.params.iter().find(|p| p.name == name)
    }
}

/// The parameter values of a control without any ([`Control::values`]).
pub(crate) fn no_values(_: &EnvConfig) -> ParamValues {
    ParamValues::new()
}

/// Sets nothing: a control without parameters ([`Control::set`]).
pub(crate) fn set_nothing(_: &mut EnvConfig, _: &ParamValues) {}

/// `compare` runs the control on every preset of its task ([`Control::in_compare`]).
pub(crate) fn always(_: &EnvConfig) -> bool {
    true
}
