//! Every task's hand-written controls in one table ([`CONTROLS`]): the name on the command line,
//! the name in a report, the task, the parameters `fairgrasp tune` may set, and how to build
//! the control as a [`fairgrasp_env::episode::Policy`]. `baseline`, `compare` and `tune` read
//! it. Each task's rows live in its folder (`planner/src/lift/controls.rs`,
//! `planner/src/place/controls.rs`, `planner/src/stack/controls.rs`): a new control is one row
//! there, a new task one line in [`TASKS`].
//!
//! - [`row`]: one row ([`Control`]) and what rows share;
//! - [`params`]: a tunable parameter ([`Param`]), its scale and bounds, values by name.

pub mod params;
pub mod row;

use fairgrasp_env::TaskKind;

use crate::lift::controls::LIFT_CONTROLS;
use crate::place::controls::PLACE_CONTROLS;
use crate::stack::controls::STACK_CONTROLS;
pub use params::{Param, ParamValues, Scale};
pub use row::Control;

/// Old path of the lift task's grip force ([`crate::lift`]'s rows), kept for one release.
pub use crate::lift::controls::GRIP;
/// Old path of [`crate::place::search_params`], kept for one release.
pub use crate::place::search_params;
/// Old paths of the force search's parameters ([`crate::place::search_params`]), kept for one
/// release.
pub use crate::place::search_params::{SEARCH, SQUARE, SWITCH, search_values, set_search};

/// Each task's rows, one line per task, in the order a comparison lists the tasks.
pub const TASKS: [&[Control]; 3] = [LIFT_CONTROLS, PLACE_CONTROLS, STACK_CONTROLS];

/// Every control of every task, each task's in the order a comparison shows them: the rows of
/// [`TASKS`] one after another.
pub static CONTROLS: [Control; row_count(&TASKS)] = concatenated(&TASKS);

/// How many rows `tasks` have together.
const fn row_count(tasks: &[&[Control]]) -> usize {
    let mut count = 0;
    let mut t = 0;
    while t < tasks.len() {
        count += tasks[t].len();
        t += 1;
    }
    count
}

/// The rows of `tasks` one after another, `N` of them (the table, built when the crate is
/// compiled: a count that is not `N`, or a first task without any row, fails the build).
const fn concatenated<const N: usize>(tasks: &[&[Control]]) -> [Control; N] {
    assert!(
        N == row_count(tasks),
        "N is not the number of the tasks' rows"
    );
    assert!(
        !tasks.is_empty() && !tasks[0].is_empty(),
        "the first task has no control"
    );
    let mut out = [tasks[0][0]; N];
    let mut k = 0;
    let mut t = 0;
    while t < tasks.len() {
        let mut r = 0;
        while r < tasks[t].len() {
            out[k] = tasks[t][r];
            k += 1;
            r += 1;
        }
        t += 1;
    }
    out
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_tasks_rows_run_one_task_of_their_own_and_every_task_has_rows() {
        let tasks: Vec<TaskKind> = TASKS
            .iter()
            .map(|rows| {
                let task = rows[0].task;
                let names: Vec<&str> = rows.iter().map(|c| c.cli).collect();
                assert!(
                    rows.iter().all(|c| c.task == task),
                    "{}'s rows {names:?} run another task too",
                    task.name()
                );
                task
            })
            .collect();
        for task in TaskKind::ALL {
            let lists = tasks.iter().filter(|&&t| t == task).count();
            assert_eq!(lists, 1, "{} has {lists} lists of rows", task.name());
        }
    }

    #[test]
    fn the_table_is_the_tasks_rows_in_order() {
        let rows: Vec<(&str, &str)> = TASKS
            .iter()
            .flat_map(|r| r.iter())
            .map(|c| (c.report, c.cli))
            .collect();
        let table: Vec<(&str, &str)> = CONTROLS.iter().map(|c| (c.report, c.cli)).collect();
        assert_eq!(table, rows);
        for task in TaskKind::ALL {
            let of_task: Vec<&str> = controls_of(task).map(|c| c.report).collect();
            let listed = TASKS.iter().find(|r| r[0].task == task).unwrap();
            let listed: Vec<&str> = listed.iter().map(|c| c.report).collect();
            assert_eq!(of_task, listed, "{}", task.name());
        }
    }
}
