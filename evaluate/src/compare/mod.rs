//! The comparison experiment: the task's scripts (its controls in the planner's table,
//! [`fairgrasp_planner::controls::CONTROLS`]) and learned policies on identical seeded scenario
//! sets, one scenario recorded for every method, and the typed result that `compare.json` holds
//! ([`fairgrasp_types::Comparison`]). Scripts are the results without a policy folder; the
//! report pairs every learned method with every script (McNemar, [`fairgrasp_types::paired`]).
//!
//! The CLI (`fairgrasp compare`) parses arguments, calls [`run_comparison`], writes the files and
//! prints; tests call [`run_comparison`] directly.
//!
//! - [`policies`]: the methods as policies (the task's scripts, then the learned policies).
//! - [`error`]: why a comparison could not run; [`event`]: its progress, for progress bars.
//! - [`record`]: recording every method on chosen scenarios (the charts' episode, the replay's).
//! - [`methods`]: a method named on the command line (`fairgrasp replay --policy`, `export
//!   --method`): a control of the preset's task by name, or a learned policy.
//! - [`spec`]: what a comparison runs, and the default presets.
//! - `schedule`: the evaluations as one queue of episodes shared by the worker threads.

pub mod error;
pub mod event;
pub mod methods;
pub mod policies;
pub mod record;
mod schedule;
pub mod spec;
pub mod tuning;

pub use error::CompareError;
pub use event::CompareEvent;
pub(crate) use policies::calibration_of;
pub use policies::{LearnedPolicy, run_folder_of, scripts_for};
pub use spec::{
    ComparePreset, CompareSpec, DEFAULT_PRESETS, DEFAULT_REPLAY_EPISODES, MAX_THREADS,
    default_threads,
};

use std::path::Path;

use fairgrasp_env::episode::trajectory::Trajectory;
use fairgrasp_env::scenario::{Scenario, scenario_set};
use fairgrasp_types::fs::slug;
use fairgrasp_types::{Comparison, MethodResult, RecordedEpisode};

/// A recorded episode's trajectory and the file stem it is saved under in `episodes/`
/// (`<method>_<preset>_ep<k>`).
#[derive(Clone, Debug)]
pub struct RecordedTrajectory {
    pub stem: String,
    pub trajectory: Trajectory,
    /// Also written as `<stem>.csv` (the episodes the charts show, for a spreadsheet).
    pub csv: bool,
}

/// The comparison and the recorded trajectories it refers to.
#[derive(Clone, Debug)]
pub struct CompareOutput {
    pub comparison: Comparison,
    /// Every recorded episode (those of `comparison.replay`, in its order, or of
    /// `comparison.recorded` when no replay was asked for); a recorded episode's `trajectory`
    /// is `episodes/<stem>.json` of one of them.
    pub episodes: Vec<RecordedTrajectory>,
}

impl CompareOutput {
    /// Writes each recorded trajectory as `<out>/episodes/<stem>.json.gz` (compact,
    /// [`Trajectory::save_compact`]), and the charts' episodes also as `<stem>.csv`.
    pub fn save_episodes(&self, out: &Path) -> Result<(), CompareError> {
        let dir = out.join("episodes");
        // The error names the file that could not be written.
        let io = |name: String| {
            let path = dir.join(name);
            move |source| CompareError::Io { path, source }
        };
        for e in &self.episodes {
            e.trajectory
                .save_compact(&dir, &e.stem)
                .map_err(io(format!("{}.json.gz", e.stem)))?;
            if e.csv {
                let name = format!("{}.csv", e.stem);
                fairgrasp_types::write_atomic(&dir.join(&name), e.trajectory.to_csv().as_bytes())
                    .map_err(io(name))?;
            }
        }
        Ok(())
    }
}

/// The seeded scenario set of one preset.
fn scenarios_of(preset: &ComparePreset, spec: &CompareSpec) -> Result<Vec<Scenario>, CompareError> {
    preset
        .config
        .validate()
        .map_err(fairgrasp_env::EnvError::from)?;
    scenario_set(&preset.config, spec.seed, spec.episodes).map_err(|e| CompareError::Preset {
        preset: preset.name.clone(),
        message: e.to_string(),
    })
}

/// Runs the scripts and every learned policy on every preset's scenario set, then records one
/// scenario of the last preset for every method.
pub fn run_comparison(
    spec: &CompareSpec,
    learned: &[LearnedPolicy],
    progress: &(dyn Fn(CompareEvent<'_>) + Sync),
) -> Result<CompareOutput, CompareError> {
    spec.check()?;
    let scripts = scripts_for(spec.presets.iter().map(|p| &p.config));
    let mut methods: Vec<String> = scripts.iter().map(|s| s.report.to_string()).collect();
    methods.extend(learned.iter().map(|l| l.name.clone()));
    let mut work = Vec::with_capacity(spec.presets.len());
    for preset in &spec.presets {
        work.push(schedule::PresetWork {
            name: &preset.name,
            config: &preset.config,
            scenarios: scenarios_of(preset, spec)?,
            calibration: calibration_of(&preset.config, &preset.name)?,
        });
    }
    let reports =
        schedule::evaluate_all(&work, &methods, &scripts, learned, spec.threads, progress)?;
    let mut reports = reports.into_iter();
    let mut results = Vec::with_capacity(work.len() * methods.len());
    for preset in &spec.presets {
        for (i, method) in methods.iter().enumerate() {
            results.push(MethodResult {
                method: method.clone(),
                preset: preset.name.clone(),
                arm: preset.config.arm.model,
                seed: spec.seed,
                policy: i
                    .checked_sub(scripts.len())
                    .map(|j| learned[j].dir.display().to_string()),
                report: reports.next().expect("a report per preset and method"),
            });
        }
    }
    let (recorded, replay, episodes) =
        record_all(spec, &work, &methods, &results, learned, progress)?;

    let comparison = Comparison {
        command: spec.command.clone(),
        presets: spec.presets.iter().map(|p| p.name.clone()).collect(),
        methods,
        preset_configs: spec
            .presets
            .iter()
            .map(|p| Ok((p.name.clone(), toml_text(p)?)))
            .collect::<Result<_, CompareError>>()?,
        run_folders: learned
            .iter()
            .filter_map(|l| run_folder_of(&l.dir))
            .map(|p| p.display().to_string())
            .collect(),
        recorded,
        replay,
        tuning: tuning::of_controls(spec, &scripts),
        results,
    };
    comparison
        .check()
        .map_err(|e| CompareError::Request(format!("inconsistent comparison: {e}")))?;
    Ok(CompareOutput {
        comparison,
        episodes,
    })
}

/// The scenarios recorded on each preset (indices into its set): the first
/// `spec.replay_episodes` and the one the charts show (`spec.episode` on the last preset, else
/// the first where the baseline and the first learned method end differently), which is often
/// a failure; only the charts' one when no replay is asked for, and then only on the last
/// preset.
/// Returns per preset the picked scenarios and the charts' one (`None`: nothing recorded).
fn picked_scenarios(
    spec: &CompareSpec,
    results: &[MethodResult],
) -> Vec<(Vec<usize>, Option<usize>)> {
    let n = spec.presets.len();
    spec.presets
        .iter()
        .enumerate()
        .map(|(p, preset)| {
            let last = p + 1 == n;
            if spec.replay_episodes == 0 && !last {
                return (Vec::new(), None);
            }
            let here: Vec<&MethodResult> =
                results.iter().filter(|r| r.preset == preset.name).collect();
            let first_differing = first_disagreement(&here).unwrap_or(0);
            let k = if last {
                spec.episode.unwrap_or(first_differing)
            } else {
                first_differing
            };
            let mut picked: Vec<usize> = (0..spec.replay_episodes.min(spec.episodes)).collect();
            if !picked.contains(&k) {
                picked.push(k);
            }
            (picked, Some(k))
        })
        .collect()
}

/// Records every method on the picked scenarios of every preset ([`picked_scenarios`]): the
/// charts' episodes (`recorded`, on the last preset), the replay's (every preset) and their
/// trajectories.
fn record_all(
    spec: &CompareSpec,
    work: &[schedule::PresetWork<'_>],
    methods: &[String],
    results: &[MethodResult],
    learned: &[LearnedPolicy],
    progress: &(dyn Fn(CompareEvent<'_>) + Sync),
) -> Result<RecordedSets, CompareError> {
    let picked = picked_scenarios(spec, results);
    let all: Vec<usize> = (0..methods.len()).collect();
    let scripts = scripts_for(spec.presets.iter().map(|p| &p.config));
    progress(CompareEvent::Recording {
        episodes: all.len() * picked.iter().map(|(p, _)| p.len()).sum::<usize>(),
    });
    let (mut recorded, mut replay, mut episodes) = (Vec::new(), Vec::new(), Vec::new());
    for (p, (preset, w)) in spec.presets.iter().zip(work).enumerate() {
        let (scenarios, Some(charts)) = &picked[p] else {
            continue;
        };
        let last = p + 1 == spec.presets.len();
        let recordings = record::record_episodes(
            &preset.config,
            &w.scenarios,
            scenarios,
            &all,
            &scripts,
            learned,
            spec.threads,
        )?;
        for r in recordings {
            let method = &methods[r.method];
            let stem = format!("{}_{}_ep{}", slug(method), slug(&preset.name), r.scenario);
            let in_charts = last && r.scenario == *charts;
            let entry = RecordedEpisode {
                method: method.clone(),
                preset: preset.name.clone(),
                episode: r.scenario,
                outcome: r.outcome,
                trajectory: format!("episodes/{stem}.json.gz"),
            };
            if in_charts {
                recorded.push(entry.clone());
            }
            if spec.replay_episodes > 0 {
                replay.push(entry);
            }
            episodes.push(RecordedTrajectory {
                stem,
                trajectory: r.trajectory,
                csv: in_charts,
            });
        }
    }
    Ok((recorded, replay, episodes))
}

/// The charts' recorded episodes, the replay's, and every trajectory they refer to.
type RecordedSets = (
    Vec<RecordedEpisode>,
    Vec<RecordedEpisode>,
    Vec<RecordedTrajectory>,
);

/// The first scenario where the baseline and the first learned method (without one, the
/// closed-loop script) end differently.
fn first_disagreement(on_last: &[&MethodResult]) -> Option<usize> {
    let a = on_last.first()?;
    let scripts = on_last.iter().take_while(|r| r.policy.is_none()).count();
    let b = on_last.get(scripts).or_else(|| on_last.get(1))?;
    a.report
        .results
        .iter()
        .zip(&b.report.results)
        .position(|(x, y)| x.outcome != y.outcome)
}

fn toml_text(p: &ComparePreset) -> Result<String, CompareError> {
    toml::to_string(&p.config).map_err(|e| CompareError::Preset {
        preset: p.name.clone(),
        message: format!("cannot write the config as TOML: {e}"),
    })
}
