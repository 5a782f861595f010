//! An episode as a servo stream for a real FR3 (`fairgrasp export`): run one method on one
//! scenario (recorded as `compare` records it), resample its joints to the controller's period
//! and check the result against the FR3's limits
//! ([`fairgrasp_planner::stream`]).

use fairgrasp_env::episode::trajectory::Recorder;
use fairgrasp_env::episode::{Outcome, run_recorded};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{Action, EnvConfig, Step, TaskEnv};
use fairgrasp_planner::stream::{
    EpisodeJoints, Resampled, StreamLimits, StreamViolation, check_stream, resample,
};

use crate::compare::methods::Method;
use crate::compare::{CompareError, calibration_of};

/// An exported episode: the stream and the episode it came from.
pub struct ExportedEpisode {
    pub resampled: Resampled,
    /// The episode's outcome in the env.
    pub outcome: Outcome,
    /// Env steps of the episode.
    pub steps: usize,
}

/// Why an episode could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    #[error(transparent)]
    Run(#[from] CompareError),
    #[error("resampling the episode's joints: {0}")]
    Resample(String),
    /// The stream crosses a limit: refused, never clipped.
    #[error("the stream crosses a limit, so nothing was written: {0}")]
    Limit(StreamViolation),
}

/// The joints, their velocities and the gripper command after the reset and every step.
#[derive(Default)]
struct JointLog {
    joints: Vec<[f64; 6]>,
    velocities: Vec<[f64; 6]>,
    gripper: Vec<f64>,
}

impl JointLog {
    fn push(&mut self, env: &TaskEnv) {
        self.joints.push(env.joints());
        self.velocities.push(env.joint_velocities());
    }
}

impl Recorder for JointLog {
    fn record_reset(&mut self, env: &TaskEnv, _opening: f64) {
        *self = JointLog::default();
        self.push(env);
    }

    fn record_step(&mut self, env: &TaskEnv, _: &Action, _: &Step, _: Option<&str>) {
        self.push(env);
        self.gripper.push(env.gripper_command());
    }
}

/// Runs `method` on `scenario` of `config` (as `compare` runs it), then resamples the episode's
/// joints to one sample every `period_sec` \[s\] followed by `hold_samples` repeats of the last,
/// with the gripper command of every step, and checks the stream against `limits` (the arm's:
/// [`StreamLimits::of`]). The episode's outcome is returned, not judged: the caller decides
/// whether a failed episode may leave.
pub fn export_episode(
    config: &EnvConfig,
    scenario: &Scenario,
    method: Method,
    period_sec: f64,
    hold_samples: usize,
    limits: &StreamLimits,
) -> Result<ExportedEpisode, ExportError> {
    method.check_task(config)?;
    let calibration = calibration_of(config, "the exported preset")?;
    let mut policy = method.policy(config, &calibration);
    let mut env = TaskEnv::new(config.clone()).map_err(CompareError::from)?;
    let mut log = JointLog::default();
    let record =
        run_recorded(&mut env, policy.as_mut(), scenario, &mut log).map_err(CompareError::from)?;
    let episode = EpisodeJoints {
        waypoints: &log.joints,
        velocities: &log.velocities,
        step_sec: config.physics.dt * config.physics.substeps as f64,
        gripper: &log.gripper,
    };
    let resampled = resample(&episode, period_sec, hold_samples, limits)
        .map_err(|e| ExportError::Resample(e.to_string()))?;
    check_stream(&resampled.stream.joints, period_sec, limits).map_err(ExportError::Limit)?;
    Ok(ExportedEpisode {
        resampled,
        outcome: record.outcome,
        steps: log.gripper.len(),
    })
}
