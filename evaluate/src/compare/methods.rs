//! A method named on the command line (`fairgrasp replay --policy P`, `fairgrasp export
//! --method M`): a hand-written control of the preset's task, by its command-line name in the
//! planner's table ([`CONTROLS`], the one list of every task's scripts), or a learned policy: a
//! shipped policy by name (`residual_hard`, …), a checkpoint folder or a run folder (its
//! `checkpoints/best`).

use fairgrasp_env::episode::Policy;
use fairgrasp_env::{EnvConfig, TaskKind};
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::{CONTROLS, Control, control, control_names};
use fairgrasp_policy::shipped::checkpoint_folder;

use crate::compare::error::CompareError;
use crate::compare::policies::LearnedPolicy;

/// Every command-line name of the table's controls, each once, in the table's order: what
/// `--method`, `--policy` and `baseline --script` accept as a script (a name can be a control of
/// several tasks, `open_loop` is the lift's baseline and the place script; the preset's task
/// picks which, [`Method::resolve`]).
pub fn script_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for c in &CONTROLS {
        if !names.contains(&c.cli) {
            names.push(c.cli);
        }
    }
    names
}

/// Each task's scripts by their command-line names, for a command's help
/// (`lift: open_loop, closed_loop, …; place: open_loop, force_search, …`).
pub fn scripts_by_task() -> String {
    TaskKind::ALL
        .iter()
        .map(|&task| format!("{}: {}", task.name(), control_names(task).join(", ")))
        .collect::<Vec<_>>()
        .join("; ")
}

/// A method to run: a control of the table or a learned policy.
pub enum Method {
    /// A hand-written control (a row of [`CONTROLS`]).
    Script(&'static Control),
    Learned(Box<LearnedPolicy>),
}

impl Method {
    /// Resolves `name` for a preset of `task`: the name of one of the task's controls, else
    /// what [`checkpoint_folder`] resolves (a shipped policy's name, a checkpoint folder or a
    /// run folder's `checkpoints/best`). The name of another task's control only is refused,
    /// naming both tasks and listing this task's scripts (it is never looked for as a folder).
    pub fn resolve(name: &str, task: TaskKind) -> Result<Method, CompareError> {
        if let Some(control) = control(task, name) {
            return Ok(Method::Script(control));
        }
        if let Some(other) = CONTROLS.iter().find(|c| c.cli == name) {
            return Err(another_tasks_script(other, task));
        }
        let dir = checkpoint_folder(name).map_err(|e| {
            CompareError::Request(format!(
                "--policy {name}: not a script of the {} task ({}), and {e}",
                task.name(),
                control_names(task).join(", ")
            ))
        })?;
        let mut loaded = LearnedPolicy::load_all(&[dir])?;
        Ok(Method::Learned(Box::new(loaded.remove(0))))
    }

    /// Refuses a script of another task than `config`'s (a method resolved for one preset and
    /// run on another): the message names both tasks and lists `config`'s scripts.
    pub fn check_task(&self, config: &EnvConfig) -> Result<(), CompareError> {
        match self {
            Method::Script(c) if c.task != config.task.kind => {
                Err(another_tasks_script(c, config.task.kind))
            }
            _ => Ok(()),
        }
    }

    /// The method's name as a comparison shows it (a control's [`Control::report`]).
    pub fn name(&self) -> String {
        match self {
            Method::Script(c) => c.report.to_string(),
            Method::Learned(l) => l.name.clone(),
        }
    }

    /// A fresh policy of this method for `config`, whose camera calibration is `calibration`,
    /// built as a comparison builds it.
    pub fn policy(&self, config: &EnvConfig, calibration: &CameraCalibration) -> Box<dyn Policy> {
        match self {
            Method::Script(c) => (c.build)(config, calibration),
            Method::Learned(l) => l.policy(config),
        }
    }
}

/// The refusal of `control`, a script of another task, on a preset of `task`: it names both
/// tasks and lists `task`'s scripts.
fn another_tasks_script(control: &Control, task: TaskKind) -> CompareError {
    CompareError::Request(format!(
        "`{}` is a script of the {} task, and this preset's task is {}: its scripts are {}",
        control.cli,
        control.task.name(),
        task.name(),
        control_names(task).join(", ")
    ))
}

/// `methods` numbered as [`record_episodes`](crate::compare::record::record_episodes) and
/// `make_policy` number a comparison's methods: their scripts first, then their learned
/// policies. Returns each method's number, in the order of `methods`, the scripts and the
/// learned policies.
pub fn numbered(methods: Vec<Method>) -> (Vec<usize>, Vec<&'static Control>, Vec<LearnedPolicy>) {
    let mut scripts = Vec::new();
    let mut learned = Vec::new();
    // Learned policies are numbered from 0 here and moved behind the scripts below.
    let mut numbers: Vec<(bool, usize)> = Vec::with_capacity(methods.len());
    for method in methods {
        match method {
            Method::Script(c) => {
                numbers.push((true, scripts.len()));
                scripts.push(c);
            }
            Method::Learned(l) => {
                numbers.push((false, learned.len()));
                learned.push(*l);
            }
        }
    }
    let numbers = numbers
        .into_iter()
        .map(|(script, i)| if script { i } else { scripts.len() + i })
        .collect();
    (numbers, scripts, learned)
}
