//! Recording episodes for the report's episode charts and its 3D replay: every method on a list
//! of scenarios of one preset, one job each on a queue shared by the threads
//! ([`fairgrasp_types::work_queue`]; an env per thread, a fresh policy per episode), returned in
//! (method, scenario) order. The recordings replay the evaluation exactly: the same scenarios,
//! the same seeds, deterministic policies.

use fairgrasp_env::episode::run_episode;
use fairgrasp_env::episode::trajectory::Trajectory;
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_types::Outcome;
use fairgrasp_types::work_queue::run_in_order;

use crate::compare::error::CompareError;
use crate::compare::policies::{LearnedPolicy, calibration_of, make_policy};
use fairgrasp_planner::controls::Control;

/// One recorded episode: method index, scenario index, outcome and trajectory.
pub struct Recording {
    /// Number of the method: an index into the scripts, then into the learned policies
    /// (`make_policy`'s numbering).
    pub method: usize,
    /// Index of the scenario in the preset's set.
    pub scenario: usize,
    pub outcome: Outcome,
    pub trajectory: Trajectory,
}

/// Runs and records every method of `methods` (indices into `scripts`, then `learned`, see
/// `make_policy`) on every scenario
/// of `picked` (indices into `scenarios`) of `config`, on `threads` threads. Returns the
/// recordings ordered by method, then by the order of `picked`.
pub fn record_episodes(
    config: &EnvConfig,
    scenarios: &[Scenario],
    picked: &[usize],
    methods: &[usize],
    scripts: &[&'static Control],
    learned: &[LearnedPolicy],
    threads: usize,
) -> Result<Vec<Recording>, CompareError> {
    let jobs: Vec<(usize, usize)> = methods
        .iter()
        .flat_map(|&m| picked.iter().map(move |&k| (m, k)))
        .collect();
    let calibration = &calibration_of(config, "the recorded preset")?;
    // Each worker makes its env with its first job (making one can fail).
    let run = |env: &mut Option<TaskEnv>, j: usize| -> Result<Recording, CompareError> {
        let env = match env {
            Some(env) => env,
            None => env.insert(TaskEnv::new(config.clone())?),
        };
        let (method, scenario) = jobs[j];
        let mut policy = make_policy(method, scripts, learned, config, calibration);
        let mut trajectory = Trajectory::default();
        let record = run_episode(
            env,
            policy.as_mut(),
            &scenarios[scenario],
            Some(&mut trajectory),
        )?;
        Ok(Recording {
            method,
            scenario,
            outcome: record.outcome,
            trajectory,
        })
    };
    run_in_order(jobs.len(), threads, &|_| {}, &|| None, &run)
}
