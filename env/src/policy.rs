//! The `Policy` trait shared by every controller (the scripted baseline, the PPO agent), and the
//! evaluation loop that runs any policy on a list of scenarios the same way.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::env::{Action, EnvError, GraspEnv};
use crate::obs::Observation;
use crate::randomize::Scenario;
use crate::task::Failure;
use crate::trajectory::Trajectory;

/// A controller: observations in, actions out.
pub trait Policy {
    /// Called at the start of every episode, with the episode's seed.
    fn reset(&mut self, seed: u64);
    /// The action for this observation.
    fn act(&mut self, obs: &Observation) -> Action;
    /// Set when the policy itself has given up (the baseline: no IK solution).
    fn gave_up(&self) -> Option<Outcome> {
        None
    }
}

/// How an episode ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// Lifted and held.
    Success,
    /// The gripper closed without both pads ever touching the object.
    MissedGrasp,
    /// The object was held and lifted, then slipped or dropped.
    SlipOrDrop,
    /// Arm or gripper hit the table or itself.
    Collision,
    /// No in-limit inverse-kinematics solution for a grasp pose.
    IkFailure,
    /// The object was pushed off the table.
    ObjectOffTable,
    /// The time limit passed without any of the above.
    Timeout,
    /// The physics state became non-finite.
    PhysicsFault,
}

/// One evaluated episode.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EpisodeResult {
    pub seed: u64,
    pub outcome: Outcome,
    pub steps: usize,
    pub episode_return: f64,
    /// Object start position in `base_link` [m], for workspace maps.
    pub object_xy: [f64; 2],
}

/// A 95 % Wilson score interval for `successes` out of `n`.
pub fn wilson_interval(successes: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let (n, p, z) = (n as f64, successes as f64 / n as f64, 1.959_963_984_540_054);
    let denominator = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denominator;
    let half = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt() / denominator;
    ((centre - half).max(0.0), (centre + half).min(1.0))
}

/// Success rate, its interval, the failure breakdown and step counts over a scenario set.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EvalReport {
    pub episodes: usize,
    pub successes: usize,
    pub success_rate: f64,
    pub ci_low: f64,
    pub ci_high: f64,
    pub collision_rate: f64,
    /// Mean steps of the successful episodes (None without any).
    pub mean_steps_to_success: Option<f64>,
    pub mean_return: f64,
    /// Episodes per outcome.
    pub outcomes: BTreeMap<Outcome, usize>,
    pub results: Vec<EpisodeResult>,
}

impl EvalReport {
    /// Summarises episode results.
    pub fn from_results(results: Vec<EpisodeResult>) -> Self {
        let n = results.len();
        let mut outcomes = BTreeMap::new();
        for r in &results {
            *outcomes.entry(r.outcome).or_insert(0) += 1;
        }
        let successes = outcomes.get(&Outcome::Success).copied().unwrap_or(0);
        let (ci_low, ci_high) = wilson_interval(successes, n);
        let success_steps: Vec<f64> = results
            .iter()
            .filter(|r| r.outcome == Outcome::Success)
            .map(|r| r.steps as f64)
            .collect();
        let rate = |k: usize| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        Self {
            episodes: n,
            successes,
            success_rate: rate(successes),
            ci_low,
            ci_high,
            collision_rate: rate(outcomes.get(&Outcome::Collision).copied().unwrap_or(0)),
            mean_steps_to_success: (!success_steps.is_empty())
                .then(|| success_steps.iter().sum::<f64>() / success_steps.len() as f64),
            mean_return: if n == 0 {
                0.0
            } else {
                results.iter().map(|r| r.episode_return).sum::<f64>() / n as f64
            },
            outcomes,
            results,
        }
    }
}

/// Runs one episode of `policy` from `scenario`; records it into `trajectory` if given.
pub fn run_episode(
    env: &mut GraspEnv,
    policy: &mut dyn Policy,
    scenario: &Scenario,
    mut trajectory: Option<&mut Trajectory>,
) -> Result<EpisodeResult, EnvError> {
    let (mut obs, _) = env.reset_to(scenario);
    policy.reset(scenario.seed);
    if let Some(t) = trajectory.as_deref_mut() {
        t.record_reset(env, obs.gripper_opening);
    }
    let cube = env.config().scene.cube_size;
    let rest_z = env.object_in_base().xyz()[2];
    let (mut held, mut lifted_while_held, mut closed_past_cube) = (false, false, false);
    let mut episode_return = 0.0;
    loop {
        let action = policy.act(&obs);
        let step = env.step(&action)?;
        if let Some(t) = trajectory.as_deref_mut() {
            t.record_step(env, &action, &step);
        }
        episode_return += step.reward;
        let both = step.obs.pad_contact[0] && step.obs.pad_contact[1];
        held |= both;
        lifted_while_held |= both && env.object_in_base().xyz()[2] - rest_z > 0.01;
        closed_past_cube |= step.obs.gripper_opening < cube - 0.005;
        obs = step.obs;
        if step.terminated || step.truncated {
            let outcome = if step.info.success {
                Outcome::Success
            } else if step.info.physics_fault.is_some() {
                Outcome::PhysicsFault
            } else if let Some(Failure::Collision(..)) = step.info.failure {
                Outcome::Collision
            } else if let Some(reason) = policy.gave_up() {
                reason
            } else if lifted_while_held {
                Outcome::SlipOrDrop
            } else if step.info.failure == Some(Failure::ObjectOffTable) {
                Outcome::ObjectOffTable
            } else if closed_past_cube && !held {
                Outcome::MissedGrasp
            } else {
                Outcome::Timeout
            };
            return Ok(EpisodeResult {
                seed: scenario.seed,
                outcome,
                steps: step.info.step,
                episode_return,
                object_xy: scenario.object_xy,
            });
        }
    }
}

/// Evaluates a fresh policy from `make` on every scenario, spread over `threads` threads (each
/// with its own env), in scenario order. Records each episode as `episode_NNNN.csv/.json` in
/// `record` if given; calls `progress` after each episode.
pub fn evaluate<P: Policy>(
    config: &crate::config::EnvConfig,
    scenarios: &[Scenario],
    threads: usize,
    record: Option<&std::path::Path>,
    make: &(dyn Fn() -> P + Sync),
    progress: &(dyn Fn() + Sync),
) -> Result<EvalReport, EnvError> {
    let chunk = scenarios.len().div_ceil(threads.max(1)).max(1);
    let mut results = Vec::with_capacity(scenarios.len());
    std::thread::scope(|scope| -> Result<(), EnvError> {
        let handles: Vec<_> = scenarios
            .chunks(chunk)
            .enumerate()
            .map(|(c, part)| {
                scope.spawn(move || -> Result<Vec<EpisodeResult>, EnvError> {
                    let mut env = GraspEnv::new(config.clone())?;
                    let mut policy = make();
                    let mut out = Vec::with_capacity(part.len());
                    for (j, scenario) in part.iter().enumerate() {
                        let mut trajectory = record.map(|_| Trajectory::default());
                        out.push(run_episode(
                            &mut env,
                            &mut policy,
                            scenario,
                            trajectory.as_mut(),
                        )?);
                        if let (Some(dir), Some(t)) = (record, &trajectory) {
                            t.save(dir, &format!("episode_{:04}", c * chunk + j))
                                .map_err(|e| EnvError::Io(format!("{}: {e}", dir.display())))?;
                        }
                        progress();
                    }
                    Ok(out)
                })
            })
            .collect();
        for h in handles {
            results.extend(h.join().expect("an evaluation thread panicked")?);
        }
        Ok(())
    })?;
    Ok(EvalReport::from_results(results))
}
