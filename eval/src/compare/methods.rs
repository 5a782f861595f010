//! A method named on the command line (`fairgrasp replay --policy P`): one of the scripts
//! (`open_loop`, `closed_loop`, `oracle`), a shipped policy by name (`residual_hard`, …), or a
//! checkpoint folder.

use std::path::{Path, PathBuf};

use crate::compare::{CompareError, LearnedPolicy, SCRIPTS};
use crate::shipped::ShippedPolicy;

/// The command-line names of the scripts, in the order of [`SCRIPTS`].
pub const SCRIPT_NAMES: [&str; 4] = ["open_loop", "closed_loop", "oracle", "calibrated"];

/// A method to run: a script (index into [`SCRIPTS`]) or a learned policy.
pub enum Method {
    Script(usize),
    Learned(Box<LearnedPolicy>),
}

impl Method {
    /// Resolves `name`: a script name, a shipped policy's name, or a checkpoint folder.
    pub fn resolve(name: &str) -> Result<Method, CompareError> {
        if let Some(i) = SCRIPT_NAMES.iter().position(|s| *s == name) {
            return Ok(Method::Script(i));
        }
        let dir = match ShippedPolicy::named(name) {
            Some(p) => p.checkpoint_dir().map_err(|e| CompareError::Io {
                path: e.path.clone(),
                source: e.source,
            })?,
            None if Path::new(name).is_dir() => PathBuf::from(name),
            None => {
                let shipped: Vec<&str> = ShippedPolicy::ALL.iter().map(|p| p.name()).collect();
                return Err(CompareError::Request(format!(
                    "--policy {name}: not a script ({}), not a shipped policy ({}), and no \
                     such checkpoint folder",
                    SCRIPT_NAMES.join(", "),
                    shipped.join(", ")
                )));
            }
        };
        let mut loaded = LearnedPolicy::load_all(&[dir])?;
        Ok(Method::Learned(Box::new(loaded.remove(0))))
    }

    /// The method's name as a comparison shows it.
    pub fn name(&self) -> String {
        match self {
            Method::Script(i) => SCRIPTS[*i].to_string(),
            Method::Learned(l) => l.name.clone(),
        }
    }
}
