//! The stack task's rows of the table of controls ([`crate::controls::CONTROLS`]): the
//! open-loop script and the force lower, in the order a comparison shows them.

use fairgrasp_env::TaskKind;

use crate::controls::row::{Control, always, no_values, set_nothing};
use crate::stack::script::{force_lower, open_loop};

/// The stack task's controls.
pub(crate) const STACK_CONTROLS: &[Control] = &[
    Control {
        cli: "open_loop",
        report: "stack script",
        task: TaskKind::Stack,
        params: &[],
        table: None,
        values: no_values,
        set: set_nothing,
        build: |env, _| Box::new(open_loop(env)),
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
        build: |env, _| Box::new(force_lower(env)),
        in_compare: always,
    },
];
