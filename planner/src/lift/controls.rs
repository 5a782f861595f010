//! The lift task's rows of the table of controls ([`crate::controls::CONTROLS`]): the
//! open-loop script, the closed-loop script, the oracle, the script after a camera calibration
//! and the script with a tuned grip, in the order a comparison shows them.

use fairgrasp_env::TaskKind;

use crate::controls::params::{Param, ParamValues, Scale};
use crate::controls::row::{Control, always, no_values, set_nothing};
use crate::lift::calibrated::CalibratedScript;
use crate::lift::closed_loop::ClosedLoopGrasp;
use crate::lift::script::{BaselineConfig, ScriptedGrasp};
use crate::lift::tuned_grip::TunedGripScript;

/// The lift task's grip force.
pub const GRIP: [Param; 1] = [Param {
    name: "grip_force",
    unit: "N",
    accepts: [0.1, 100.0],
    range: [2.0, 30.0],
    scale: Scale::Log,
    doc: "the squeeze per finger",
}];

/// The lift task's controls.
pub(crate) const LIFT_CONTROLS: &[Control] = &[
    Control {
        cli: "open_loop",
        report: "scripted baseline",
        task: TaskKind::Lift,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(ScriptedGrasp::new(env, BaselineConfig::default())),
        in_compare: always,
    },
    Control {
        cli: "closed_loop",
        report: "closed-loop script",
        task: TaskKind::Lift,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(ClosedLoopGrasp::observed(env)),
        in_compare: always,
    },
    Control {
        cli: "oracle",
        report: "oracle script",
        task: TaskKind::Lift,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(ClosedLoopGrasp::oracle(env)),
        in_compare: always,
    },
    Control {
        cli: "calibrated",
        report: "script + calibration",
        task: TaskKind::Lift,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, calibration| Box::new(CalibratedScript::new(env, calibration.clone())),
        in_compare: always,
    },
    Control {
        cli: "tuned_grip",
        report: "script + tuned grip",
        task: TaskKind::Lift,
        params: &GRIP,
        table: Some("control"),
        values: |env| {
            let f = env.control.grip_force.unwrap_or(env.gripper.force);
            ParamValues::from([("grip_force".to_string(), f)])
        },
        set: |env, values| {
            if let Some(&f) = values.get("grip_force") {
                env.control.grip_force = Some(f);
            }
        },
        build: |env, _| Box::new(TunedGripScript::new(env)),
        in_compare: always,
    },
];
