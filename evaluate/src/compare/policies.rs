//! The methods a comparison runs, as policies: the task's scripts first ([`scripts_for`]),
//! then the learned policies loaded from their checkpoint folders ([`LearnedPolicy`]);
//! `make_policy` builds a fresh policy of method `i`.

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use fairgrasp_env::episode::Policy;
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::{Control, controls_of};

use crate::compare::error::CompareError;
use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::checkpoint::{self, CheckpointMeta, actor_policy};

/// The name of the scripted baseline (the open-loop script) in every comparison.
pub const BASELINE: &str = "scripted baseline";

/// The scripts every comparison runs first, in order: the open-loop baseline, the closed-loop
/// script (re-plans on the observed cube, retries once), the oracle (the closed loop on the
/// true pose: the ceiling), the open-loop script after a simulated camera calibration (the
/// engineer's fix for a miscalibrated cell, [`fairgrasp_planner::calibrated`]) and the
/// open-loop script with the grip tuned for the cell (the contact family's control,
/// [`fairgrasp_planner::tuned_grip`]; the open-loop script where the preset tunes none).
pub const SCRIPTS: [&str; 5] = [
    BASELINE,
    "closed-loop script",
    "oracle script",
    "script + calibration",
    "script + tuned grip",
];

/// The place task's scripts, in order: the open-loop place script, the same with the
/// force-guided search, tuned on training scenarios, in place of its lower
/// ([`fairgrasp_planner::place_search`]), and both in closed loop (the cube re-observed in the
/// hand before the place is planned, `ScriptedPlace::reobserving`).
pub const PLACE_SCRIPTS: [&str; 4] = [
    "place script",
    "place script + force search",
    "closed-loop place",
    "closed-loop place + force search",
];

/// The controls a comparison of `configs` (presets of one task) runs first: the task's controls
/// ([`fairgrasp_planner::controls::CONTROLS`]) that any of the presets runs by default, in the
/// table's order ([`SCRIPTS`] for the lift task, [`PLACE_SCRIPTS`] and, with a place cell's
/// mix, its controls). Method `i` of a comparison is control `i` while `i` is below their
/// number, then the learned policies in order (`make_policy`).
pub fn scripts_for<'a>(configs: impl IntoIterator<Item = &'a EnvConfig>) -> Vec<&'static Control> {
    let configs: Vec<&EnvConfig> = configs.into_iter().collect();
    let Some(task) = configs.first().map(|c| c.task.kind) else {
        return Vec::new();
    };
    controls_of(task)
        .filter(|c| configs.iter().any(|env| (c.in_compare)(env)))
        .collect()
}

/// A learned policy loaded from its checkpoint folder, with its name in the comparison.
pub struct LearnedPolicy {
    /// `"<mode> PPO: <run folder name>"`, made unique with a ` (n)` suffix.
    pub name: String,
    /// The checkpoint folder.
    pub dir: PathBuf,
    pub meta: CheckpointMeta,
    /// Its actor, run without burn ([`fairgrasp_policy::actor`]).
    pub actor: Actor,
}

impl LearnedPolicy {
    /// Loads every checkpoint folder in `dirs`, naming each after its mode and run folder.
    pub fn load_all(dirs: &[PathBuf]) -> Result<Vec<Self>, CompareError> {
        let mut out: Vec<Self> = Vec::new();
        for dir in dirs {
            let (meta, actor) = checkpoint::load_actor(dir)?;
            let folder = run_folder_of(dir).unwrap_or_else(|| dir.clone());
            let label = folder
                .file_name()
                .map_or("policy".into(), |n| n.to_string_lossy().into_owned());
            let mode = serde_name(&meta.agent.mode);
            let mut name = format!("{mode} PPO: {label}");
            if out.iter().any(|l| l.name == name) {
                name = format!("{name} ({})", out.len() + 1);
            }
            out.push(Self {
                name,
                dir: dir.clone(),
                meta,
                actor,
            });
        }
        Ok(out)
    }
}

/// A unit enum's serde name (`Mode::Residual` → `residual`).
fn serde_name<T: serde::Serialize>(value: &T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_else(|| "unnamed".into())
}

/// The run folder a checkpoint folder belongs to: the nearest of its two ancestors that holds
/// `metrics.csv` (`run/checkpoints/best` → `run`, `policy/checkpoint` → `policy`).
pub fn run_folder_of(checkpoint: &Path) -> Option<PathBuf> {
    checkpoint
        .ancestors()
        .skip(1)
        .take(2)
        .find(|d| d.join("metrics.csv").is_file())
        .map(Path::to_path_buf)
}

/// A fresh policy of method `i` (`scripts` in order, then `learned` in order) for `config`,
/// whose camera calibration is `calibration`.
pub(crate) fn make_policy(
    i: usize,
    scripts: &[&'static Control],
    learned: &[LearnedPolicy],
    config: &EnvConfig,
    calibration: &CameraCalibration,
) -> Box<dyn Policy> {
    match scripts.get(i) {
        Some(control) => (control.build)(config, calibration),
        None => {
            let l = &learned[i - scripts.len()];
            Box::new(actor_policy(&l.meta, &l.actor, config))
        }
    }
}

/// The simulated camera calibration of a config's cell, for "script + calibration".
pub(crate) fn calibration_of(
    config: &EnvConfig,
    preset: &str,
) -> Result<CameraCalibration, CompareError> {
    CameraCalibration::of(config).map_err(|message| CompareError::Preset {
        preset: preset.to_string(),
        message,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use fairgrasp_env::TaskKind;

    /// The name lists are the table's names, in its order (they are not a second list of the
    /// controls to keep in step: a control added to the table and not here fails this).
    #[test]
    fn the_script_names_are_the_tables() {
        let names = |task| controls_of(task).map(|c| c.report).collect::<Vec<_>>();
        assert_eq!(names(TaskKind::Lift), SCRIPTS.to_vec());
        assert_eq!(names(TaskKind::Place)[..PLACE_SCRIPTS.len()], PLACE_SCRIPTS);
        // A place preset without a mix runs the four; the place cell adds its three.
        let place = fairgrasp_env::config::presets::load("place").unwrap();
        let cell = fairgrasp_env::config::presets::load("place_cell").unwrap();
        assert_eq!(scripts_for([&place]).len(), PLACE_SCRIPTS.len());
        assert_eq!(scripts_for([&cell]).len(), PLACE_SCRIPTS.len() + 3);
        assert_eq!(scripts_for([&place, &cell]).len(), PLACE_SCRIPTS.len() + 3);
    }
}
