//! Running a comparison's evaluations: every (preset, unit, scenario) is one job of a queue
//! shared by the worker threads ([`fairgrasp_types::work_queue`]). A unit is the four scripts
//! together, run in lockstep ([`run_lockstep`]: one simulation for the scripts whose actions
//! agree at every step, as at least two of them do on most scenarios of every default preset),
//! or one learned policy. No worker waits for another to finish a method's share before the
//! next method starts (as one evaluation per method, split in fixed chunks of one per thread,
//! did), and the outcomes are the same: an episode depends only on its scenario and its method,
//! never on the episodes its env or policy ran before (`compare --threads 1` and `--threads 3`
//! give identical per-episode results), nor on the methods it ran in lockstep with.
//!
//! A worker keeps one env per preset and the policies of one (preset, unit) while its jobs stay
//! on them, as one thread of [`fairgrasp_env::episode::evaluate`] does for its share.

use std::ops::Range;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use fairgrasp_env::episode::{EpisodeRecord, EvalReport, Policy, run_lockstep};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_planner::CameraCalibration;
use fairgrasp_types::work_queue::run_in_order;

use crate::compare::error::CompareError;
use crate::compare::event::CompareEvent;
use crate::compare::policies::{LearnedPolicy, make_policy};
use fairgrasp_planner::controls::Control;

/// One preset's share of a comparison: its name, config, scenario set and camera calibration.
pub(crate) struct PresetWork<'a> {
    pub name: &'a str,
    pub config: &'a EnvConfig,
    pub scenarios: Vec<Scenario>,
    pub calibration: CameraCalibration,
}

/// A worker's env (with the index of its preset) and the policies of one unit (with its preset
/// and unit).
type WorkerState = (
    Option<(usize, TaskEnv)>,
    Option<((usize, usize), Vec<Box<dyn Policy>>)>,
);

/// The units of `methods` (the scripts first, then the learned policies, as [`make_policy`]
/// numbers them): the scripts together, then each learned policy alone; as ranges of methods.
fn units(methods: usize, scripts: usize) -> Vec<Range<usize>> {
    let scripts = scripts.min(methods);
    std::iter::once(0..scripts)
        .chain((scripts..methods).map(|m| m..m + 1))
        .filter(|u| !u.is_empty())
        .collect()
}

/// Evaluates every method (`methods`: the scripts' and learned policies' names, see
/// [`make_policy`]) on every preset's scenario set, on `threads` workers; returns the reports in
/// (preset, method) order. Progress: `Method` when a (preset, method) gets its first episode
/// (in that order), `Episode` after each, `MethodDone` when its last one is in.
pub(crate) fn evaluate_all(
    presets: &[PresetWork<'_>],
    methods: &[String],
    scripts: &[&'static Control],
    learned: &[LearnedPolicy],
    threads: usize,
    progress: &(dyn Fn(CompareEvent<'_>) + Sync),
) -> Result<Vec<EvalReport>, CompareError> {
    // Every preset's set has the spec's episode count.
    let episodes = presets.first().map_or(0, |p| p.scenarios.len());
    debug_assert!(presets.iter().all(|p| p.scenarios.len() == episodes));
    let units = units(methods.len(), scripts.len());
    let cells = presets.len() * methods.len();
    // Job j is (preset, unit, scenario) in that nesting.
    let locate = |j: usize| {
        (
            j / (units.len() * episodes),
            (j / episodes) % units.len(),
            j % episodes,
        )
    };
    // Per (preset, method): its episodes as they finish, and how many are still out.
    let finished: Vec<Mutex<Vec<Option<EpisodeRecord>>>> = (0..cells)
        .map(|_| Mutex::new(vec![None; episodes]))
        .collect();
    let remaining: Vec<AtomicUsize> = (0..cells).map(|_| AtomicUsize::new(episodes)).collect();
    let on_claim = |j: usize| {
        let (p, u, k) = locate(j);
        if k == 0 {
            for m in units[u].clone() {
                progress(CompareEvent::Method {
                    preset: presets[p].name,
                    method: &methods[m],
                });
            }
        }
    };
    let run = |(env, policies): &mut WorkerState, j: usize| -> Result<(), CompareError> {
        let (p, u, k) = locate(j);
        let work = &presets[p];
        let env = match env {
            Some((q, env)) if *q == p => env,
            _ => &mut env.insert((p, TaskEnv::new(work.config.clone())?)).1,
        };
        let policies = match policies {
            Some((key, policies)) if *key == (p, u) => policies,
            _ => {
                let made = units[u]
                    .clone()
                    .map(|m| make_policy(m, scripts, learned, work.config, &work.calibration))
                    .collect();
                &mut policies.insert(((p, u), made)).1
            }
        };
        let records = run_lockstep(env, policies, &work.scenarios[k])?;
        for (m, record) in units[u].clone().zip(records) {
            let cell = p * methods.len() + m;
            finished[cell].lock().unwrap_or_else(|e| e.into_inner())[k] = Some(record);
            let (preset, method) = (work.name, methods[m].as_str());
            progress(CompareEvent::Episode { preset, method });
            if remaining[cell].fetch_sub(1, Ordering::AcqRel) == 1 {
                let done = finished[cell].lock().unwrap_or_else(|e| e.into_inner());
                let successes = done.iter().flatten().filter(|r| r.success()).count();
                progress(CompareEvent::MethodDone {
                    preset,
                    method,
                    success_rate: successes as f64 / episodes as f64,
                });
            }
        }
        Ok(())
    };
    let jobs = presets.len() * units.len() * episodes;
    run_in_order(jobs, threads, &on_claim, &|| (None, None), &run)?;
    Ok(finished
        .into_iter()
        .map(|cell| {
            let records = cell.into_inner().unwrap_or_else(|e| e.into_inner());
            EvalReport::from_results(
                records
                    .into_iter()
                    .map(|r| r.expect("every episode ran: the queue returned no error"))
                    .collect(),
            )
        })
        .collect())
}
