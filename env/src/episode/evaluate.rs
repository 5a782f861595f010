//! The `Policy` trait shared by every controller (the scripted baseline, the PPO agent), and the
//! evaluation loop that runs any policy on a list of scenarios the same way.

use crate::env::obs::Observation;
use crate::env::{Action, EnvError, Step, TaskEnv};
use crate::episode::trajectory::{Recorder, Trajectory};
use crate::scenario::Scenario;
use crate::scenario::perception::{ObservedObject, true_object};

/// The result types, shared with the report crate through `fairgrasp-types` (one schema).
pub use fairgrasp_types::{EpisodeRecord, EvalReport, Outcome, wilson_interval};

/// A controller: observations in, actions out.
pub trait Policy {
    /// Called at the start of every episode, with the episode's seed.
    fn reset(&mut self, seed: u64);
    /// The action for this observation.
    fn act(&mut self, obs: &Observation) -> Action;
    /// The object's true pose, given by [`run_episode`] before every `act` (the env's truth, not
    /// the perception model's report). Only an oracle uses it (the ceiling a controller could
    /// reach); every other policy ignores it (the default).
    fn observe_truth(&mut self, _truth: &ObservedObject) {}
    /// Set when the policy itself has given up (the baseline: no IK solution).
    fn gave_up(&self) -> Option<Outcome> {
        None
    }
    /// The phase the policy is in after its latest `act` (a script's `approach`, `descend`,
    /// `close`, …), recorded with each step of a trajectory for replays; `None` (the default)
    /// for a policy without phases.
    fn phase(&self) -> Option<&'static str> {
        None
    }
    /// The squeeze per finger \[N\] the policy asks for with its latest `act` (applied before the
    /// step, as [`TaskEnv::set_grip_force`]); `None` (the default) keeps the env's.
    fn grip_force(&self) -> Option<f64> {
        None
    }
}

/// A boxed policy is a policy: every method goes to the box's content, so no adapter has to
/// list them (one that forgot `grip_force` once made a squeezing residual squeeze nothing).
impl<P: Policy + ?Sized> Policy for Box<P> {
    fn reset(&mut self, seed: u64) {
        (**self).reset(seed);
    }
    fn act(&mut self, obs: &Observation) -> Action {
        (**self).act(obs)
    }
    fn observe_truth(&mut self, truth: &ObservedObject) {
        (**self).observe_truth(truth);
    }
    fn gave_up(&self) -> Option<Outcome> {
        (**self).gave_up()
    }
    fn phase(&self) -> Option<&'static str> {
        (**self).phase()
    }
    fn grip_force(&self) -> Option<f64> {
        (**self).grip_force()
    }
}

/// Runs one episode of `policy` from `scenario`; records it into `trajectory` if given.
pub fn run_episode(
    env: &mut TaskEnv,
    policy: &mut dyn Policy,
    scenario: &Scenario,
    trajectory: Option<&mut Trajectory>,
) -> Result<EpisodeRecord, EnvError> {
    match trajectory {
        Some(t) => run_recorded(env, policy, scenario, t),
        None => run_recorded(env, policy, scenario, &mut NoRecord),
    }
}

/// A [`Recorder`] that keeps nothing.
struct NoRecord;

impl Recorder for NoRecord {
    fn record_reset(&mut self, _: &TaskEnv, _: f64) {}
    fn record_step(&mut self, _: &TaskEnv, _: &Action, _: &Step, _: Option<&str>) {}
}

/// Runs one episode of `policy` from `scenario`, handing the reset and every step to `recorder`.
pub fn run_recorded(
    env: &mut TaskEnv,
    policy: &mut dyn Policy,
    scenario: &Scenario,
    recorder: &mut dyn Recorder,
) -> Result<EpisodeRecord, EnvError> {
    let (mut obs, _) = env.reset_to(scenario);
    policy.reset(scenario.seed);
    recorder.record_reset(env, obs.gripper_opening);
    loop {
        policy.observe_truth(&true_object(env.mount(), &env.object_in_base()));
        let action = policy.act(&obs);
        if let Some(force) = policy.grip_force() {
            env.set_grip_force(force)?;
        }
        let step = env.step(&action)?;
        recorder.record_step(env, &action, &step, policy.phase());
        obs = step.obs;
        if let Some(record) = step.info.episode {
            return Ok(record.with_policy_verdict(policy.gave_up()));
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
                scope.spawn(move || -> Result<Vec<EpisodeRecord>, EnvError> {
                    let mut env = TaskEnv::new(config.clone())?;
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
                            let stem = format!("episode_{:04}", c * chunk + j);
                            t.save(dir, &stem).map_err(|e| {
                                let file = dir.join(format!("{stem}.csv/.json"));
                                EnvError::Io(format!("{}: {e}", file.display()))
                            })?;
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

/// Evaluates a fresh policy from `make` on the `n` scenarios that `seed` draws for `config` (the
/// set every method meets for this seed), like [`evaluate`].
pub fn evaluate_seeded<P: Policy>(
    config: &crate::config::EnvConfig,
    seed: u64,
    n: usize,
    threads: usize,
    record: Option<&std::path::Path>,
    make: &(dyn Fn() -> P + Sync),
    progress: &(dyn Fn() + Sync),
) -> Result<EvalReport, EnvError> {
    let scenarios = crate::scenario::scenario_set(config, seed, n)?;
    evaluate(config, &scenarios, threads, record, make, progress)
}
