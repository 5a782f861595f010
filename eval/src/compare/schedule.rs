//! Running a comparison's evaluations: every (preset, method, scenario) episode is one job, and
//! `threads` workers claim jobs one at a time in that order until none is left. No worker waits
//! for a method's slowest half to finish before the next method starts (as one evaluation per
//! method, each split in fixed halves, did), and the outcomes are the same: an episode depends
//! only on its scenario and its method, never on the episodes its env or policy ran before
//! (`compare --threads 1` and `--threads 3` give identical per-episode results).
//!
//! A worker keeps one env per preset and one policy per (preset, method) while its jobs stay on
//! them, as one thread of [`fairgrasp_env::episode::evaluate`] does for its share.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use fairgrasp_env::episode::{EpisodeRecord, EvalReport, Policy, run_episode};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvConfig, GraspEnv};
use fairgrasp_planner::CameraCalibration;

use crate::compare::{CompareError, CompareEvent, LearnedPolicy, make_policy};

/// One preset's share of a comparison: its name, config, scenario set and camera calibration.
pub(crate) struct PresetWork<'a> {
    pub name: &'a str,
    pub config: &'a EnvConfig,
    pub scenarios: Vec<Scenario>,
    pub calibration: CameraCalibration,
}

/// One (preset, method) evaluation being filled in by the workers.
struct Cell {
    /// Its episodes by scenario index, as they finish.
    episodes: Mutex<Vec<Option<EpisodeRecord>>>,
    /// Episodes not finished yet; the worker that finishes the last one writes the report.
    remaining: AtomicUsize,
    report: Mutex<Option<EvalReport>>,
}

/// Where job `j` is: (preset, method, scenario).
struct Layout {
    methods: usize,
    /// Scenarios per preset (every preset's set has the same length).
    episodes: usize,
    jobs: usize,
}

impl Layout {
    fn locate(&self, j: usize) -> (usize, usize, usize) {
        let per_preset = self.methods * self.episodes;
        (
            j / per_preset,
            (j % per_preset) / self.episodes,
            j % self.episodes,
        )
    }
}

/// Evaluates every method (`methods`: the scripts' and learned policies' names, see
/// [`make_policy`]) on every preset's scenario set, on `threads` workers; returns the reports in
/// (preset, method) order. Progress: `Method` when a (preset, method) gets its first episode
/// (in that order), `Episode` after each, `MethodDone` when its last one is in.
pub(crate) fn evaluate_all(
    presets: &[PresetWork<'_>],
    methods: &[String],
    learned: &[LearnedPolicy],
    threads: usize,
    progress: &(dyn Fn(CompareEvent<'_>) + Sync),
) -> Result<Vec<EvalReport>, CompareError> {
    let episodes = presets.first().map_or(0, |p| p.scenarios.len());
    if presets.iter().any(|p| p.scenarios.len() != episodes) {
        return Err(CompareError::Request(
            "every preset needs the same number of scenarios".into(),
        ));
    }
    let layout = Layout {
        methods: methods.len(),
        episodes,
        jobs: presets.len() * methods.len() * episodes,
    };
    let cells: Vec<Cell> = (0..presets.len() * methods.len())
        .map(|_| Cell {
            episodes: Mutex::new(vec![None; episodes]),
            remaining: AtomicUsize::new(episodes),
            report: Mutex::new(None),
        })
        .collect();
    // The next job; claimed under the lock so that `Method` events come in job order.
    let next = Mutex::new(0usize);
    let failed = AtomicBool::new(false);
    let claim = || -> Option<usize> {
        let mut next = next.lock().unwrap_or_else(|p| p.into_inner());
        if *next >= layout.jobs || failed.load(Ordering::Relaxed) {
            return None;
        }
        let j = *next;
        *next += 1;
        let (p, m, k) = layout.locate(j);
        if k == 0 {
            progress(CompareEvent::Method {
                preset: presets[p].name,
                method: &methods[m],
            });
        }
        Some(j)
    };
    let worker = || -> Result<(), CompareError> {
        let mut env: Option<(usize, GraspEnv)> = None;
        let mut policy: Option<((usize, usize), Box<dyn Policy>)> = None;
        while let Some(j) = claim() {
            let (p, m, k) = layout.locate(j);
            let work = &presets[p];
            if env.as_ref().is_none_or(|(q, _)| *q != p) {
                env = Some((p, GraspEnv::new(work.config.clone())?));
            }
            if policy.as_ref().is_none_or(|(key, _)| *key != (p, m)) {
                let made = make_policy(m, learned, work.config, &work.calibration);
                policy = Some(((p, m), made));
            }
            let (Some((_, env)), Some((_, policy))) = (env.as_mut(), policy.as_mut()) else {
                unreachable!("both were set above");
            };
            let record = run_episode(env, policy.as_mut(), &work.scenarios[k], None)?;
            let cell = &cells[p * layout.methods + m];
            cell.episodes.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(record);
            progress(CompareEvent::Episode {
                preset: work.name,
                method: &methods[m],
            });
            if cell.remaining.fetch_sub(1, Ordering::AcqRel) == 1 {
                let results: Vec<EpisodeRecord> =
                    std::mem::take(&mut *cell.episodes.lock().unwrap_or_else(|e| e.into_inner()))
                        .into_iter()
                        .map(|r| r.expect("every episode of a finished cell is in"))
                        .collect();
                let report = EvalReport::from_results(results);
                progress(CompareEvent::MethodDone {
                    preset: work.name,
                    method: &methods[m],
                    success_rate: report.success_rate,
                });
                *cell.report.lock().unwrap_or_else(|e| e.into_inner()) = Some(report);
            }
        }
        Ok(())
    };
    let outcomes: Vec<Result<(), CompareError>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads.clamp(1, layout.jobs.max(1)))
            .map(|_| {
                scope.spawn(|| {
                    let r = worker();
                    if r.is_err() {
                        failed.store(true, Ordering::Relaxed);
                    }
                    r
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a comparison worker panicked"))
            .collect()
    });
    outcomes.into_iter().collect::<Result<(), _>>()?;
    Ok(cells
        .into_iter()
        .map(|c| {
            c.report
                .into_inner()
                .unwrap_or_else(|e| e.into_inner())
                .expect("every cell finished")
        })
        .collect())
}
