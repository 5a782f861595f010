//! Playing a joint stream back in the env: the arm starts at the stream's first sample (the
//! blocking move a real controller makes first), then tracks the samples as a servo controller
//! does (linear between samples: per physics substep, the stream's velocity plus a feedback on
//! the distance to it, within the FR3's rate limits), with the stream's gripper commands; the
//! env judges the episode as usual.

use fairgrasp_env::episode::Outcome;
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::{EnvError, ServoSetpoint, TaskEnv};

use crate::stream::servo::ServoStream;

/// What a playback did.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaybackReport {
    /// The env's outcome for the episode.
    pub outcome: Outcome,
    /// Env steps taken.
    pub steps: usize,
    /// Largest distance between a joint and the stream at the end of an env step \[rad\] (the
    /// servo arm's lag behind the samples).
    pub max_tracking_error: f64,
    /// Largest difference between the stream's first sample and the scenario's own start
    /// joints \[rad\] (0 for a stream exported from this scenario).
    pub start_offset: f64,
}

/// Why a stream could not be played.
#[derive(Debug, thiserror::Error)]
pub enum PlaybackError {
    #[error(
        "the stream has no gripper commands, so it cannot grasp: export it without --no-gripper"
    )]
    NoGripper,
    #[error("the stream has no samples")]
    Empty,
    #[error(transparent)]
    Env(#[from] EnvError),
}

/// Plays `stream` in `env` on `scenario`, with the arm placed at the stream's first sample,
/// until the env ends the episode (success, failure, or its step limit).
pub fn play(
    env: &mut TaskEnv,
    scenario: &Scenario,
    stream: &ServoStream,
) -> Result<PlaybackReport, PlaybackError> {
    let start = *stream.joints.first().ok_or(PlaybackError::Empty)?;
    if stream.gripper.is_empty() {
        return Err(PlaybackError::NoGripper);
    }
    let start_offset = (0..6)
        .map(|i| (start[i] - scenario.start_joints[i]).abs())
        .fold(0.0, f64::max);
    let mut placed = *scenario;
    placed.start_joints = start;
    env.reset_to(&placed);
    let physics = &env.config().physics;
    let (dt, substeps) = (physics.dt, physics.substeps);
    let env_dt = dt * substeps as f64;
    let mut max_tracking_error: f64 = 0.0;
    for k in 0.. {
        let t0 = k as f64 * env_dt;
        let setpoints: Vec<ServoSetpoint> = (0..substeps)
            .map(|j| {
                let t = t0 + j as f64 * dt;
                let (position, next) = (stream.joints_at(t), stream.joints_at(t + dt));
                // A gripper event takes effect from its sample's time on.
                let sample = (t / stream.period_sec + 1e-9).floor() as usize;
                ServoSetpoint {
                    position,
                    velocity: std::array::from_fn(|i| (next[i] - position[i]) / dt),
                    gripper: stream.gripper_at(sample).unwrap_or(-1.0),
                }
            })
            .collect();
        let step = env.step_servo(&setpoints)?;
        let reached = stream.joints_at(t0 + env_dt);
        let q = step.obs.joints;
        let error = (0..6)
            .map(|i| (q[i] - reached[i]).abs())
            .fold(0.0, f64::max);
        max_tracking_error = max_tracking_error.max(error);
        if let Some(record) = step.info.episode {
            return Ok(PlaybackReport {
                outcome: record.outcome,
                steps: k + 1,
                max_tracking_error,
                start_offset,
            });
        }
    }
    unreachable!("the env ends every episode within its step limit")
}
