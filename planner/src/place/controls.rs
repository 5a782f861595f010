//! The place task's rows of the table of controls ([`crate::controls::CONTROLS`]): the
//! open-loop script, the force-guided search, both re-observing the pocket, squaring before the
//! search, the switching search and its oracle (a ceiling), in the order a comparison shows
//! them; and how `tune` reads and sets their parameters in a preset's `[task.place]` tables.

use fairgrasp_env::{EnvConfig, TaskKind};

use crate::controls::params::ParamValues;
use crate::controls::row::{Control, always, no_values, set_nothing};
use crate::place::oracle_switch::OracleSwitch;
use crate::place::script::ScriptedPlace;
use crate::place::search_params::{SEARCH, SQUARE, SWITCH, search_values, set_search};

/// A place cell's preset (one family's error per cycle, unlabelled).
fn has_mix(env: &EnvConfig) -> bool {
    env.task.place.mix.is_some()
}

/// The squaring control's values (`[task.place.square]`, its search's behind `search_`).
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

/// Sets the squaring control's values in `[task.place.square]`.
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

/// The switching search's values (`[task.place.switch]`: each setting's behind `pose_` and
/// `tilted_`, and the tilt band).
fn switch_values(env: &EnvConfig) -> ParamValues {
    let s = &env.task.place.switch;
    let wall = env.task.place.wall_height;
    let mut v = prefixed(search_values(&s.pose, wall), "pose_");
    v.extend(prefixed(search_values(&s.tilted, wall), "tilted_"));
    v.insert("tilt_band".to_string(), s.tilt_band);
    v
}

/// Sets the switching search's values in `[task.place.switch]`.
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

/// The force search's values (`[task.place.search]`).
fn force_search_values(env: &EnvConfig) -> ParamValues {
    search_values(&env.task.place.search, env.task.place.wall_height)
}

/// Sets the force search's values in `[task.place.search]`.
fn set_force_search(env: &mut EnvConfig, values: &ParamValues) {
    set_search(&mut env.task.place.search, values, "");
}

/// The place task's controls.
pub(crate) const PLACE_CONTROLS: &[Control] = &[
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
        values: force_search_values,
        set: set_force_search,
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
        values: force_search_values,
        set: set_force_search,
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
];
