//! A method named on the command line (`fairgrasp replay --policy P`): one of the scripts
//! (`open_loop`, `closed_loop`, `oracle`, `calibrated`, `tuned_grip`), a shipped policy by name
//! (`residual_hard`, …), a checkpoint folder or a run folder (its `checkpoints/best`).

use crate::compare::error::CompareError;
use crate::compare::policies::{LearnedPolicy, SCRIPTS};
use fairgrasp_policy::shipped::checkpoint_folder;

/// The command-line names of the scripts, in the order of [`SCRIPTS`].
pub const SCRIPT_NAMES: [&str; 5] = [
    "open_loop",
    "closed_loop",
    "oracle",
    "calibrated",
    "tuned_grip",
];

/// A method to run: a script (index into [`SCRIPTS`]) or a learned policy.
pub enum Method {
    Script(usize),
    Learned(Box<LearnedPolicy>),
}

impl Method {
    /// Resolves `name`: a script name, else what [`checkpoint_folder`] resolves (a shipped
    /// policy's name, a checkpoint folder or a run folder's `checkpoints/best`).
    pub fn resolve(name: &str) -> Result<Method, CompareError> {
        if let Some(i) = SCRIPT_NAMES.iter().position(|s| *s == name) {
            return Ok(Method::Script(i));
        }
        let dir = checkpoint_folder(name).map_err(|e| {
            CompareError::Request(format!(
                "--policy {name}: not a script ({}), and {e}",
                SCRIPT_NAMES.join(", ")
            ))
        })?;
        let mut loaded = LearnedPolicy::load_all(&[dir])?;
        Ok(Method::Learned(Box::new(loaded.remove(0))))
    }

    /// Refuses a lift script on a place preset (`config`): there `open_loop` is the place
    /// script, and the other script names mean nothing (the force search runs in `baseline
    /// --script force_search` and in `compare`).
    pub fn check_task(&self, config: &fairgrasp_env::EnvConfig) -> Result<(), CompareError> {
        match self {
            Method::Script(i) if *i > 0 && config.task.kind == fairgrasp_env::TaskKind::Place => {
                Err(CompareError::Request(format!(
                    "`{}` is a lift task's script; on a place preset the script is open_loop \
                     (the place script)",
                    SCRIPT_NAMES[*i]
                )))
            }
            _ => Ok(()),
        }
    }

    /// The method's name as a comparison shows it.
    pub fn name(&self) -> String {
        match self {
            Method::Script(i) => SCRIPTS[*i].to_string(),
            Method::Learned(l) => l.name.clone(),
        }
    }
}
