//! A task's settings are its own: a preset carries only its own task's table (`[task.place]`,
//! `[task.stack]`) besides the shared ones, and a draw that cannot be made names the table whose
//! numbers make it impossible. On the code before this rule, a stack preset took `[task.place]
//! grip_tilt` (its script fell from 100 % to 0 %) and `[task.place.mix]` (the second cube's
//! camera error vanished) without a word, and a second cube with no place was blamed on
//! `randomization.radius`.

use fairgrasp_env::config::presets::{self, PRESETS};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvConfig, TaskKind};

/// Every key each task's table sets in the shipped presets of that task (as written), with the
/// line that sets it: `(task, key, TOML text)`.
fn table_settings() -> Vec<(TaskKind, String, String)> {
    let mut out = Vec::new();
    for (name, text, _) in PRESETS {
        let kind = presets::load(name).unwrap().task.kind;
        let doc: toml::Table = toml::from_str(text).unwrap();
        let Some(table) = doc
            .get("task")
            .and_then(|t| t.get(kind.name()))
            .and_then(|t| t.as_table())
        else {
            continue;
        };
        for (key, value) in table {
            let mut one = toml::Table::new();
            one.insert(key.clone(), value.clone());
            let mut own = toml::Table::new();
            own.insert(kind.name().to_string(), toml::Value::Table(one));
            let mut task = toml::Table::new();
            task.insert("task".into(), toml::Value::Table(own));
            let text = toml::to_string(&task).unwrap();
            if !out.iter().any(|(k, name, _)| *k == kind && name == key) && sets(kind, &text) {
                out.push((kind, key.clone(), text));
            }
        }
    }
    out
}

/// Whether `extra` sets its table away from the defaults (`takt = 20.0` is the default), on a
/// config of `kind` (a setting refused there, as a mix with no error to mix, sets it).
fn sets(kind: TaskKind, extra: &str) -> bool {
    let task = format!("[task]\nkind = \"{}\"\n", kind.name());
    let plain = EnvConfig::from_toml_str(&task).unwrap();
    EnvConfig::from_toml_str(&with(&task, extra))
        .ok()
        .is_none_or(|c| c != plain)
}

/// `text` with the tables of `extra` laid over it (the extra tables appended).
fn with(text: &str, extra: &str) -> String {
    let mut doc: toml::Table = toml::from_str(text).unwrap();
    let extra: toml::Table = toml::from_str(extra).unwrap();
    let task = doc
        .entry("task")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()))
        .as_table_mut()
        .unwrap();
    for (name, table) in extra["task"].as_table().unwrap() {
        let own = task
            .entry(name.clone())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .unwrap();
        for (k, v) in table.as_table().unwrap() {
            own.insert(k.clone(), v.clone());
        }
    }
    toml::to_string(&doc).unwrap()
}

#[test]
fn a_preset_carrying_another_tasks_table_is_refused_naming_the_table_and_its_task() {
    let settings = table_settings();
    // The place cell's mix, grip tilt and friction, the stack's sector: all are walked.
    for key in ["mix", "grip_tilt", "fixture_friction", "search", "square"] {
        assert!(
            settings
                .iter()
                .any(|(k, name, _)| *k == TaskKind::Place && name == key),
            "[task.place] {key} is not in a shipped preset"
        );
    }
    assert!(
        settings
            .iter()
            .any(|(k, name, _)| *k == TaskKind::Stack && name == "observed_position_noise")
    );
    let mut checked = 0;
    for (name, text, _) in PRESETS {
        let own = presets::load(name).unwrap().task.kind;
        for (kind, key, extra) in &settings {
            let combined = with(text, extra);
            let result = EnvConfig::from_toml_str(&combined);
            if *kind == own {
                // Its own table's settings, from another preset of its task: taken, or refused
                // by a rule of their own (a mix needs errors to mix), never as another task's.
                if let Err(e) = result {
                    assert!(
                        !e.to_string().contains("a config carries only"),
                        "{name}: {e}"
                    );
                }
                continue;
            }
            let table = kind.name();
            let message = match result {
                Ok(_) => panic!("{name} ({}) took [task.{table}] {key}", own.name()),
                Err(e) => e.to_string(),
            };
            assert!(
                message.contains(&format!("task.{table}.{key}"))
                    && message.contains(&format!("[task.{table}] is the {table} task's table"))
                    && message.contains(&format!("task.kind = \"{}\"", own.name())),
                "{name} with [task.{table}] {key}: {message}"
            );
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} combinations refused");
}

#[test]
fn the_issues_examples_are_refused_on_a_stack_preset() {
    let stack = PRESETS.iter().find(|(n, _, _)| *n == "stack").unwrap().1;
    for (extra, field) in [
        (
            "[task.place]\ngrip_tilt = [0.07, 0.17]\n",
            "task.place.grip_tilt",
        ),
        (
            "[task.place.mix]\nfixture_error = 1.0\ngrasp_error = 1.0\ntilted = 0.0\n",
            "task.place.mix",
        ),
    ] {
        let e = EnvConfig::from_toml_str(&format!("{stack}\n{extra}"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(field)
                && e.contains("[task.place] is the place task's table")
                && e.contains("task.kind = \"stack\""),
            "{e}"
        );
    }
    // A place preset with a second cube's sector.
    let place = PRESETS.iter().find(|(n, _, _)| *n == "place").unwrap().1;
    let e = EnvConfig::from_toml_str(&format!(
        "{place}\n[task.stack]\nbase_radius = [0.3, 0.4]\n"
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("task.stack.base_radius") && e.contains("task.kind = \"place\""),
        "{e}"
    );
    // Its own defaults written out are no other task's settings: a run folder's config.toml
    // holds every field, and loads.
    for (name, _, _) in PRESETS {
        let full = presets::load(name).unwrap().to_toml();
        EnvConfig::from_toml_str(&full).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn a_second_cube_with_no_place_is_blamed_on_its_own_table() {
    let stack = presets::load("stack").unwrap();
    // Never 1 m from a cube drawn within 0.35 m of the base, when it stands within 0.3 m.
    let mut drawn = stack.clone();
    drawn.task.stack.base_radius = [0.25, 0.3];
    drawn.task.stack.min_distance_from_cube = 1.0;
    drawn.validate().unwrap();
    let e = Scenario::sample(&drawn, 0).unwrap_err().to_string();
    assert!(
        e.contains("[task.stack]")
            && e.contains("task.stack.base_radius [0.25, 0.3]")
            && e.contains("task.stack.min_distance_from_cube 1 m")
            && !e.starts_with("no graspable object position"),
        "{e}"
    );
    // A fixed second cube out of reach.
    let mut fixed = stack.clone();
    fixed.task.stack.randomize = false;
    fixed.task.stack.base_xy = [1.5, 0.0];
    fixed.validate().unwrap();
    let e = Scenario::sample(&fixed, 0).unwrap_err().to_string();
    assert!(
        e.contains("[task.stack]") && e.contains("task.stack.base_xy [1.5, 0.0]"),
        "{e}"
    );
    // A cube out of reach is still the cube's sector's.
    let mut cube = stack;
    cube.randomization.radius = [0.9, 1.0];
    let e = Scenario::sample(&cube, 0).unwrap_err().to_string();
    assert!(e.contains("randomization.radius"), "{e}");
}
