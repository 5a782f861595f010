//! A method named on the command line resolves as every other name of a policy does: a script
//! of the preset's task (a control of the planner's table, by name), a shipped policy, a
//! checkpoint folder or a run folder (its `checkpoints/best`); another task's script is refused
//! naming both tasks, anything else with what it could have been.

use std::path::PathBuf;

use fairgrasp_env::TaskKind;
use fairgrasp_env::config::presets;
use fairgrasp_evaluate::compare::methods::{Method, numbered, script_names};
use fairgrasp_planner::controls::CONTROLS;
use fairgrasp_policy::shipped::ShippedPolicy;

/// The task of preset `name`.
fn task_of(name: &str) -> TaskKind {
    presets::load(name).unwrap().task.kind
}

/// The report name of the script `name` resolves to on a preset of `task`.
fn script_report(name: &str, task: TaskKind) -> &'static str {
    match Method::resolve(name, task) {
        Ok(Method::Script(c)) => c.report,
        Ok(Method::Learned(_)) => panic!("{name} resolved to a learned policy"),
        Err(e) => panic!("{name} on {}: {e}", task.name()),
    }
}

/// The message `name` is refused with on a preset of `task`.
fn refusal(name: &str, task: TaskKind) -> String {
    match Method::resolve(name, task) {
        Err(e) => e.to_string(),
        Ok(m) => panic!("{name} on {} resolved to {}", task.name(), m.name()),
    }
}

#[test]
fn a_method_is_a_script_a_shipped_policy_a_checkpoint_or_a_run_folder() {
    let lift = task_of("sector");
    assert_eq!(script_report("closed_loop", lift), "closed-loop script");
    let resolve = |name: &str| Method::resolve(name, lift).unwrap();
    let shipped = resolve("residual_nudged");
    assert!(matches!(shipped, Method::Learned(_)));
    // A run folder: the shipped checkpoint copied to RUN/checkpoints/best.
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("methods-run-folder");
    let _ = std::fs::remove_dir_all(&root);
    let best = root.join("my_run/checkpoints/best");
    std::fs::create_dir_all(&best).unwrap();
    let source = ShippedPolicy::ResidualNudged.checkpoint_dir().unwrap();
    for f in ["meta.json", "model.bpk", "checksum"] {
        std::fs::copy(source.join(f), best.join(f)).unwrap();
    }
    let run = root.join("my_run");
    let Method::Learned(from_run) = resolve(run.to_str().unwrap()) else {
        panic!("a run folder is a learned policy");
    };
    assert_eq!(from_run.dir, best);
    let Method::Learned(from_checkpoint) = resolve(best.to_str().unwrap()) else {
        panic!("a checkpoint folder is a learned policy");
    };
    assert_eq!(from_checkpoint.meta, from_run.meta);
    // A folder that is neither is refused naming the task's scripts and the shipped policies.
    let e = refusal(root.to_str().unwrap(), lift);
    assert!(
        e.contains(
            "not a script of the lift task (open_loop, closed_loop, oracle, calibrated, tuned_grip)"
        ) && e.contains("residual_generalist")
            && e.contains("run folder"),
        "{e}"
    );
}

/// A script's name means the preset's task's control: `open_loop` is the lift task's baseline
/// and the place script; a name only another task has is refused, naming both tasks and listing
/// the preset's scripts, and a script resolved for one task is refused on the other's preset.
#[test]
fn a_script_name_is_a_control_of_the_presets_task_and_another_tasks_is_refused() {
    let (lift, place) = (task_of("sector"), task_of("place"));
    assert_ne!(lift, place);
    assert_eq!(script_report("open_loop", lift), "scripted baseline");
    assert_eq!(script_report("open_loop", place), "place script");
    assert_eq!(script_report("closed_loop", place), "closed-loop place");
    assert_eq!(
        script_report("force_search", place),
        "place script + force search"
    );
    let e = refusal("force_search", lift);
    assert!(
        e.contains("`force_search` is a script of the place task")
            && e.contains("this preset's task is lift")
            && e.contains("open_loop, closed_loop, oracle, calibrated, tuned_grip"),
        "{e}"
    );
    let e = refusal("calibrated", place);
    assert!(
        e.contains("`calibrated` is a script of the lift task")
            && e.contains("this preset's task is place")
            && e.contains("open_loop, force_search, closed_loop, closed_loop_force_search"),
        "{e}"
    );
    let sector = presets::load("sector").unwrap();
    let place_preset = presets::load("place").unwrap();
    let closed = Method::resolve("closed_loop", lift).unwrap();
    assert!(closed.check_task(&sector).is_ok());
    let e = closed.check_task(&place_preset).unwrap_err().to_string();
    assert!(
        e.contains("`closed_loop` is a script of the lift task")
            && e.contains("this preset's task is place")
            && e.contains("force_search"),
        "{e}"
    );
}

/// Every control of the table is reached by its name on its task's presets (no name of a task
/// is two of its controls, and no two controls share a report name), and the names the command
/// line accepts are the table's, each once.
#[test]
fn every_control_of_the_table_resolves_by_its_name() {
    for control in &CONTROLS {
        match Method::resolve(control.cli, control.task) {
            // The table is a `const`: its rows are compared by their names, not their address.
            Ok(Method::Script(c)) => assert_eq!(
                (c.report, c.task),
                (control.report, control.task),
                "{}",
                control.cli
            ),
            _ => panic!("{} ({}) does not resolve", control.cli, control.task.name()),
        }
    }
    for (i, a) in CONTROLS.iter().enumerate() {
        assert!(
            CONTROLS[i + 1..].iter().all(|b| b.report != a.report),
            "{}",
            a.report
        );
    }
    let names = script_names();
    for control in &CONTROLS {
        assert_eq!(
            names.iter().filter(|n| **n == control.cli).count(),
            1,
            "{}",
            control.cli
        );
    }
    assert!(names.iter().all(|n| CONTROLS.iter().any(|c| c.cli == *n)));
}

/// Methods named in any order are numbered as a comparison numbers them: the scripts first,
/// then the learned policies, each keeping its name.
#[test]
fn named_methods_are_numbered_scripts_first() {
    let lift = task_of("sector");
    let named = ["residual_nudged", "oracle", "open_loop"];
    let methods: Vec<Method> = named
        .iter()
        .map(|n| Method::resolve(n, lift).unwrap())
        .collect();
    let names: Vec<String> = methods.iter().map(Method::name).collect();
    let (numbers, scripts, learned) = numbered(methods);
    assert_eq!(numbers, [2, 0, 1]);
    let reports: Vec<&str> = scripts.iter().map(|c| c.report).collect();
    assert_eq!(reports, ["oracle script", "scripted baseline"]);
    assert_eq!(learned.len(), 1);
    assert_eq!(names[0], learned[0].name);
    assert_eq!(names[1..], ["oracle script", "scripted baseline"]);
}
