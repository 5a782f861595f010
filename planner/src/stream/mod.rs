//! A joint stream for a real FR3 controller: an episode's joints resampled to the controller's
//! servo period with Ruckig ([`mod@resample`]), checked against the FR3's limits before anything is
//! written ([`check`]), encoded as JSON, CSV or NumPy `.npy` ([`mod@file`]), and played back in the
//! env ([`playback`]) so that what leaves the simulator is what was evaluated.
//!
//! Joints are in FAIRINO's order j1 … j6, radians in memory, degrees in files. The stream starts
//! where the arm must be brought first (a blocking `MoveJ` on a real arm), then runs one sample
//! per period (`ServoJ`), then repeats its final sample `hold_samples` times so that the arm
//! settles before the servo mode ends.

pub mod check;
pub mod file;
pub mod playback;
pub mod resample;

use std::ops::RangeInclusive;

use fairgrasp_kinematics::ArmModel;

pub use check::{Quantity, StreamViolation, check_stream};
pub use playback::{PlaybackError, PlaybackReport, play};
pub use resample::{EpisodeJoints, Resampled, resample};

/// Servo periods accepted \[s\]: FAIRINO's ROS 2 driver accepts 1–16 ms for `ServoJ`.
pub const PERIOD_RANGE_SEC: RangeInclusive<f64> = 0.001..=0.016;
/// The default servo period \[s\] (`ServoJ`'s own default `cmdT`).
pub const DEFAULT_PERIOD_SEC: f64 = 0.008;
/// The largest change of one joint between two samples \[deg\]: the driver's guard
/// (`servo_j.maximum_joint_step_deg`).
pub const MAX_STEP_DEG: f64 = 1.0;
/// The joint acceleration limit streams are checked against \[rad/s²\]: FAIRINO publishes none;
/// 10 rad/s² is fairgrasp's own (docs/FR3.md), the limit the simulated arm moves with.
pub const MAX_ACCELERATION: f64 = 10.0;

/// What a stream must respect, per joint, in radians.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StreamLimits {
    /// Soft joint limits \[rad\] (FAIRINO's user manual).
    pub lower: [f64; 6],
    pub upper: [f64; 6],
    /// Joint velocity limits \[rad/s\] (FAIRINO's user manual).
    pub max_velocity: [f64; 6],
    /// Joint acceleration limit \[rad/s²\].
    pub max_acceleration: f64,
    /// Largest change of a joint between two samples \[rad\].
    pub max_step: f64,
}

impl StreamLimits {
    /// The limits of `model` (FR3: docs/FR3.md), with [`MAX_ACCELERATION`] and [`MAX_STEP_DEG`].
    pub fn of(model: &ArmModel) -> Self {
        Self {
            lower: model.joints.map(|j| j.lower),
            upper: model.joints.map(|j| j.upper),
            max_velocity: model.joints.map(|j| j.max_velocity),
            max_acceleration: MAX_ACCELERATION,
            max_step: MAX_STEP_DEG.to_radians(),
        }
    }
}

/// A gripper command that takes effect at a sample and holds until the next event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GripperEvent {
    /// Index of the sample at which it takes effect.
    pub sample: usize,
    /// The env's gripper command: −1 open … +1 closed (the fingers' target travel is
    /// `(command + 1)/2` of their 42.5 mm).
    pub command: f64,
}

/// A joint stream at a fixed period.
#[derive(Clone, Debug, PartialEq)]
pub struct ServoStream {
    /// Time between samples \[s\].
    pub period_sec: f64,
    /// The samples \[rad\], j1 … j6; the first is the start (reached by a blocking move), the
    /// last `hold_samples` repeat the final one.
    pub joints: Vec<[f64; 6]>,
    /// How many of the last samples repeat the final position.
    pub hold_samples: usize,
    /// Gripper events in sample order (empty: the stream carries no gripper commands).
    pub gripper: Vec<GripperEvent>,
}

impl ServoStream {
    /// The gripper command in effect at sample `n`, if the stream carries gripper events.
    pub fn gripper_at(&self, n: usize) -> Option<f64> {
        let first = self.gripper.first()?;
        let latest = self.gripper.iter().take_while(|e| e.sample <= n).last();
        Some(latest.unwrap_or(first).command)
    }

    /// The joints \[rad\] at time `t` \[s\] from the first sample: linear between samples (as a
    /// servo controller interpolates), the final sample after the end.
    pub fn joints_at(&self, t: f64) -> [f64; 6] {
        let last = self.joints.len().saturating_sub(1);
        let x = (t / self.period_sec).max(0.0);
        let n = (x.floor() as usize).min(last);
        if n >= last {
            return self.joints[last];
        }
        let f = x - n as f64;
        let (a, b) = (self.joints[n], self.joints[n + 1]);
        std::array::from_fn(|i| a[i] + f * (b[i] - a[i]))
    }

    /// Duration from the first to the last sample \[s\].
    pub fn duration_sec(&self) -> f64 {
        self.joints.len().saturating_sub(1) as f64 * self.period_sec
    }
}
