//! The methods a comparison runs, as policies: the task's scripts first ([`scripts_for`], rows
//! of the planner's table of controls), then the learned policies loaded from their checkpoint
//! folders ([`LearnedPolicy`]); `make_policy` builds a fresh policy of method `i`.

use std::path::{Path, PathBuf};

use fairgrasp_env::EnvConfig;
use fairgrasp_env::episode::Policy;
use fairgrasp_planner::CameraCalibration;
use fairgrasp_planner::controls::{Control, controls_of};

use crate::compare::error::CompareError;
use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::checkpoint::{self, CheckpointMeta, actor_policy};

/// The controls a comparison of `configs` (presets of one task) runs first: the task's controls
/// in the planner's table ([`fairgrasp_planner::controls::CONTROLS`], the one list of every
/// task's scripts) that any of the presets runs by default ([`Control::in_compare`]), in the
/// table's order. Each is shown under its [`Control::report`] name. Method `i` of a comparison
/// is control `i` while `i` is below their number, then the learned policies in order
/// (`make_policy`).
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

    /// A fresh policy of this learned method for `config`: its actor, run without burn.
    pub fn policy(&self, config: &EnvConfig) -> Box<dyn Policy> {
        Box::new(actor_policy(&self.meta, &self.actor, config))
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
        None => learned[i - scripts.len()].policy(config),
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

    fn reports(configs: &[&EnvConfig]) -> Vec<&'static str> {
        scripts_for(configs.iter().copied())
            .iter()
            .map(|c| c.report)
            .collect()
    }

    /// A comparison runs the scripts it ran when evaluate kept its own lists of them, in the
    /// same order and under the same names (compare.csv's method column): the lift task's five,
    /// the place task's four, and with a place cell's mix its three more; presets of one task
    /// together run every script any of them runs.
    #[test]
    fn a_comparison_runs_its_tasks_scripts_in_the_tables_order() {
        let load = |name| fairgrasp_env::config::presets::load(name).unwrap();
        let (sector, place, cell) = (load("sector"), load("place"), load("place_cell"));
        assert_eq!(
            reports(&[&sector]),
            [
                "scripted baseline",
                "closed-loop script",
                "oracle script",
                "script + calibration",
                "script + tuned grip",
            ]
        );
        let place_scripts = [
            "place script",
            "place script + force search",
            "closed-loop place",
            "closed-loop place + force search",
        ];
        assert_eq!(reports(&[&place]), place_scripts);
        let mut with_mix = place_scripts.to_vec();
        with_mix.extend([
            "squaring + force search",
            "force search, switch",
            "force search, oracle switch (ceiling)",
        ]);
        assert_eq!(reports(&[&cell]), with_mix);
        assert_eq!(reports(&[&place, &cell]), with_mix);
        assert!(
            scripts_for([&cell])
                .iter()
                .all(|c| c.task == cell.task.kind)
        );
        assert!(scripts_for([]).is_empty());
    }
}
