//! Recording episodes for the report's episode charts and its 3D replay: every method on a list
//! of scenarios of one preset, spread over threads (each with its own env and a fresh policy per
//! episode, claiming episodes one at a time), returned in (method, scenario) order. The recordings replay the evaluation exactly: the same
//! scenarios, the same seeds, deterministic policies.

use std::sync::atomic::{AtomicUsize, Ordering};

use fairgrasp_env::episode::run_episode;
use fairgrasp_env::episode::trajectory::Trajectory;
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvConfig, GraspEnv};
use fairgrasp_types::Outcome;

use crate::compare::{CompareError, LearnedPolicy, calibration_of, make_policy};

/// One recorded episode: method index, scenario index, outcome and trajectory.
pub struct Recording {
    /// Index of the method ([`crate::compare::SCRIPTS`], then the learned policies).
    pub method: usize,
    /// Index of the scenario in the preset's set.
    pub scenario: usize,
    pub outcome: Outcome,
    pub trajectory: Trajectory,
}

/// Runs and records every method of `methods` (indices, see [`make_policy`]) on every scenario
/// of `picked` (indices into `scenarios`) of `config`, on `threads` threads. Returns the
/// recordings ordered by method, then by the order of `picked`.
pub fn record_episodes(
    config: &EnvConfig,
    scenarios: &[Scenario],
    picked: &[usize],
    methods: &[usize],
    learned: &[LearnedPolicy],
    threads: usize,
) -> Result<Vec<Recording>, CompareError> {
    let jobs: Vec<(usize, usize)> = methods
        .iter()
        .flat_map(|&m| picked.iter().map(move |&k| (m, k)))
        .collect();
    let calibration = &calibration_of(config, "the recorded preset")?;
    // Workers claim jobs one at a time (an episode's recording does not depend on which
    // worker runs it), then the recordings are put back in job order.
    let next = AtomicUsize::new(0);
    let worker = || -> Result<Vec<(usize, Recording)>, CompareError> {
        let mut env = GraspEnv::new(config.clone())?;
        let mut done = Vec::new();
        loop {
            let j = next.fetch_add(1, Ordering::Relaxed);
            let Some(&(method, scenario)) = jobs.get(j) else {
                return Ok(done);
            };
            let mut policy = make_policy(method, learned, config, calibration);
            let mut trajectory = Trajectory::default();
            let record = run_episode(
                &mut env,
                policy.as_mut(),
                &scenarios[scenario],
                Some(&mut trajectory),
            )?;
            done.push((
                j,
                Recording {
                    method,
                    scenario,
                    outcome: record.outcome,
                    trajectory,
                },
            ));
        }
    };
    let mut out = std::thread::scope(|scope| -> Result<Vec<(usize, Recording)>, CompareError> {
        let handles: Vec<_> = (0..threads.clamp(1, jobs.len().max(1)))
            .map(|_| scope.spawn(worker))
            .collect();
        let mut all = Vec::with_capacity(jobs.len());
        for h in handles {
            all.extend(h.join().expect("a recording thread panicked")?);
        }
        Ok(all)
    })?;
    out.sort_by_key(|(j, _)| *j);
    Ok(out.into_iter().map(|(_, r)| r).collect())
}
