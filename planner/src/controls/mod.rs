//! Every task's hand-written controls in one table ([`CONTROLS`]): the name on the command line,
//! the name in a report, the task, the parameters `fairgrasp tune` may set, and how to build
//! the control as a [`Policy`]. `baseline`, `compare` and `tune` read it; a new control is one
//! row here.
//!
//! - [`params`]: a tunable parameter ([`Param`]), its scale and bounds, values by name;
//! - [`search_params`]: the force search's parameters ([`SEARCH`]) and how values set them.

pub mod params;
pub mod search_params;

use fairgrasp_env::episode::Policy;
use fairgrasp_env::{EnvConfig, TaskKind};

use crate::oracle_switch::OracleSwitch;
use crate::{
    BaselineConfig, CalibratedScript, CameraCalibration, ClosedLoopGrasp, ScriptedGrasp,
    ScriptedPlace, TunedGripScript,
};
pub use params::{Param, ParamValues, Scale};
pub use search_params::{SEARCH, SQUARE, SWITCH, search_values, set_search};

/// One hand-written control. Its parameters live in the env's config (one table per control,
/// [`Control::table`]), so that a tuned setting is a preset fragment and every command that
/// reads a preset runs the control as tuned.
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

fn no_values(_: &EnvConfig) -> ParamValues {
    ParamValues::new()
}

fn set_nothing(_: &mut EnvConfig, _: &ParamValues) {}

fn always(_: &EnvConfig) -> bool {
    true
}

/// A place cell's preset (one family's error per cycle, unlabelled).
fn has_mix(env: &EnvConfig) -> bool {
    env.task.place.mix.is_some()
}

fn square_values(env: &EnvConfig) -> ParamValues {
    let q = &env.task.place.square;
    let mut v = prefixed(
        search_values(&q.search, env.task.place.wall_height),
        "search_",
    );
    for (k, x) in [
        ("offset", q.offset),
        ("speed", q.speed),
        ("force", q.force),
        ("press", q.press),
        ("hold", q.hold),
        ("squeeze", q.squeeze),
    ] {
        v.insert(k.to_string(), x);
    }
    v
}

fn set_square(env: &mut EnvConfig, values: &ParamValues) {
    let q = &mut env.task.place.square;
    set_search(&mut q.search, values, "search_");
    for (k, slot) in [
        ("offset", &mut q.offset),
        ("speed", &mut q.speed),
        ("force", &mut q.force),
        ("press", &mut q.press),
        ("hold", &mut q.hold),
        ("squeeze", &mut q.squeeze),
    ] {
        if let Some(&x) = values.get(k) {
            *slot = x;
        }
    }
}

fn switch_values(env: &EnvConfig) -> ParamValues {
    let s = &env.task.place.switch;
    let wall = env.task.place.wall_height;
    let mut v = prefixed(search_values(&s.pose, wall), "pose_");
    v.extend(prefixed(search_values(&s.tilted, wall), "tilted_"));
    v.insert("tilt_band".to_string(), s.tilt_band);
    v
}

fn set_switch(env: &mut EnvConfig, values: &ParamValues) {
    let s = &mut env.task.place.switch;
    set_search(&mut s.pose, values, "pose_");
    set_search(&mut s.tilted, values, "tilted_");
    if let Some(&x) = values.get("tilt_band") {
        s.tilt_band = x;
    }
}

/// `values` with each name behind `prefix`.
fn prefixed(values: ParamValues, prefix: &str) -> ParamValues {
    values
        .into_iter()
        .map(|(k, v)| (format!("{prefix}{k}"), v))
        .collect()
}

fn place_search_values(env: &EnvConfig) -> ParamValues {
    search_values(&env.task.place.search, env.task.place.wall_height)
}

fn set_place_search(env: &mut EnvConfig, values: &ParamValues) {
    set_search(&mut env.task.place.search, values, "");
}

/// The lift task's grip force.
pub const GRIP: [Param; 1] = [Param {
    name: "grip_force",
    unit: "N",
    accepts: [0.1, 100.0],
    range: [2.0, 30.0],
    scale: Scale::Log,
    doc: "the squeeze per finger",
}];

/// Every control of every task, each task's in the order a comparison shows them.
pub static CONTROLS: [Control; 14] = [
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
    Control {
        cli: "open_loop",
        report: "place script",
        task: TaskKind::Place,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(ScriptedPlace::new(env)),
        in_compare: always,
    },
    Control {
        cli: "force_search",
        report: "place script + force search",
        task: TaskKind::Place,
        params: &SEARCH,
        table: Some("task.place.search"),
        values: place_search_values,
        set: set_place_search,
        build: |env, _| Box::new(ScriptedPlace::with_search(env, env.task.place.search)),
        in_compare: always,
    },
    Control {
        cli: "closed_loop",
        report: "closed-loop place",
        task: TaskKind::Place,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(ScriptedPlace::new(env).reobserving()),
        in_compare: always,
    },
    Control {
        cli: "closed_loop_force_search",
        report: "closed-loop place + force search",
        task: TaskKind::Place,
        params: &SEARCH,
        table: Some("task.place.search"),
        values: place_search_values,
        set: set_place_search,
        build: |env, _| {
            Box::new(ScriptedPlace::with_search(env, env.task.place.search).reobserving())
        },
        in_compare: always,
    },
    Control {
        cli: "square_search",
        report: "squaring + force search",
        task: TaskKind::Place,
        params: &SQUARE,
        table: Some("task.place.square"),
        values: square_values,
        set: set_square,
        build: |env, _| Box::new(ScriptedPlace::with_squaring(env, env.task.place.square)),
        in_compare: has_mix,
    },
    Control {
        cli: "switch_search",
        report: "force search, switch",
        task: TaskKind::Place,
        params: &SWITCH,
        table: Some("task.place.switch"),
        values: switch_values,
        set: set_switch,
        build: |env, _| Box::new(ScriptedPlace::with_switch(env, env.task.place.switch)),
        in_compare: has_mix,
    },
    Control {
        cli: "oracle_switch",
        report: "force search, oracle switch (ceiling)",
        task: TaskKind::Place,
        params: &SWITCH,
        table: Some("task.place.switch"),
        values: switch_values,
        set: set_switch,
        build: |env, _| Box::new(OracleSwitch::new(env)),
        in_compare: has_mix,
    },
    Control {
        cli: "open_loop",
        report: "stack script",
        task: TaskKind::Stack,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(crate::stack::open_loop(env)),
        in_compare: always,
    },
    Control {
        cli: "force_lower",
        report: "stack script + force lower",
        task: TaskKind::Stack,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(crate::stack::force_lower(env)),
        in_compare: always,
    },
];

/// The controls of `task`, in a comparison's order.
pub fn controls_of(task: TaskKind) -> impl Iterator<Item = &'static Control> {
    CONTROLS.iter().filter(move |c| c.task == task)
}

/// The control of `task` called `cli` on the command line.
pub fn control(task: TaskKind, cli: &str) -> Option<&'static Control> {
    controls_of(task).find(|c| c.cli == cli)
}

/// The command-line names of `task`'s controls, for an error that lists them.
pub fn control_names(task: TaskKind) -> Vec<&'static str> {
    controls_of(task).map(|c| c.cli).collect()
}
