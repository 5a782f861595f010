//! The run folder's copy of the preset file a run was started with (`RUN/env.toml`): a resume
//! trains on it wherever it is started, since a relative `preset` names another file elsewhere.
//! Made and used by `fairgrasp-rl`'s `run::resume::training_config` and `config_for_run`; read by
//! [`crate::recipe::Recipe::from_toml_file_in`].

use std::path::{Path, PathBuf};

/// The copy's name inside the run folder.
pub const ENV_SNAPSHOT: &str = "env.toml";

/// The run's copy of its preset file, if `preset` names a file and the run kept a copy.
pub fn env_snapshot_of(preset: &str, run_dir: &Path) -> Option<PathBuf> {
    let snapshot = run_dir.join(ENV_SNAPSHOT);
    (preset.ends_with(".toml") && snapshot.is_file()).then_some(snapshot)
}
