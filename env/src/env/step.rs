//! The values that cross the Env API: actions, step results, info, errors.

use serde::Serialize;

use crate::config::validate::ConfigError;
use fairgrasp_types::EpisodeRecord;

use crate::env::obs::Observation;
use crate::env::spaces::ACT_DIM;
use crate::scenario::{Scenario, UngraspableRegion};
use crate::task::Failure;

/// One action: joint-velocity commands j1 … j6 and the gripper command, each in [-1, 1].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Action(pub [f64; ACT_DIM]);

impl Action {
    /// Hold the joints, gripper open.
    pub fn hold_open() -> Self {
        Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0])
    }

    /// From any slice of 7 numbers (e.g. a policy's `f32` output).
    pub fn from_slice(values: &[f32]) -> Result<Self, EnvError> {
        let array: [f32; ACT_DIM] = values
            .try_into()
            .map_err(|_| EnvError::ActionLength(values.len()))?;
        Ok(Action(array.map(f64::from)))
    }
}

/// What a servo controller holds for one physics substep: where the joints should be at its
/// start, how fast they should move through it, and the gripper command during it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoSetpoint {
    /// Joint angles \[rad\] at the start of the substep.
    pub position: [f64; 6],
    /// Joint velocities \[rad/s\] through the substep.
    pub velocity: [f64; 6],
    /// Gripper command in [-1, 1] (-1 open, +1 closed).
    pub gripper: f64,
}

/// What else happened in a step.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Info {
    /// Steps taken in this episode.
    pub step: usize,
    /// The object is lifted and held.
    pub success: bool,
    /// Why the episode failed, if it did.
    pub failure: Option<Failure>,
    /// Deepest penetration of the reported collision \[m\].
    pub collision_depth_m: Option<f64>,
    /// A non-finite physics state ended the episode (as truncated): what was found.
    pub physics_fault: Option<String>,
    /// This step ran rigid-body physics (false: a free-space step, see `physics.free_space`).
    pub simulated: bool,
    /// The scenario this episode started from.
    pub scenario: Option<Scenario>,
    /// The episode's record, on its terminal step (terminated or truncated) only.
    pub episode: Option<EpisodeRecord>,
}

/// The result of `step`.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub obs: Observation,
    pub reward: f64,
    pub terminated: bool,
    pub truncated: bool,
    pub info: Info,
}

/// Misuse of the environment.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EnvError {
    #[error(
        "action[{index}] = {value} is not finite (actions are 6 joint velocities + 1 gripper command, each in [-1, 1])"
    )]
    NonFiniteAction { index: usize, value: f64 },
    #[error("an action has 7 values (6 joints + gripper), got {0}")]
    ActionLength(usize),
    #[error("a servo step takes one setpoint per physics substep: {expected} expected, got {got}")]
    SetpointCount { expected: usize, got: usize },
    #[error("servo setpoint {substep}: {what} is not finite")]
    NonFiniteSetpoint { substep: usize, what: String },
    #[error("grip force {0} N: must be finite and in (0, 100] N (gripper.force's range)")]
    GripForce(f64),
    #[error("the episode has ended (terminated or truncated): call reset first")]
    EpisodeOver,
    #[error("a vectorised step takes one action per environment: {expected} expected, got {got}")]
    ActionCount { expected: usize, got: usize },
    #[error("a vectorised env needs at least one env config")]
    NoConfigs,
    #[error("an environment worker thread stopped (it panicked): the vectorised env cannot go on")]
    WorkerLost,
    #[error(transparent)]
    Config(#[from] ConfigError),
    #[error("cannot write: {0}")]
    Io(String),
    #[error(transparent)]
    Ungraspable(#[from] UngraspableRegion),
}
