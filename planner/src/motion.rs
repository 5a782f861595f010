//! Jerk-limited, time-synchronised joint trajectories (Ruckig, via the pure-Rust `rsruckig`).

use rsruckig::prelude::*;
use serde::Serialize;

/// Limits of a joint trajectory, per joint.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MotionLimits {
    /// \[rad/s\]
    pub max_velocity: [f64; 6],
    /// \[rad/s²\]
    pub max_acceleration: [f64; 6],
    /// \[rad/s³\]
    pub max_jerk: [f64; 6],
}

/// Why a trajectory could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("Ruckig could not plan the joint trajectory: {0}")]
pub struct MotionError(pub String);

/// A planned joint trajectory from a start state to a target at rest.
pub struct JointTrajectory {
    trajectory: Trajectory<6>,
    target: [f64; 6],
}

fn daov(values: [f64; 6]) -> DataArrayOrVec<f64, 6> {
    daov_stack![
        values[0], values[1], values[2], values[3], values[4], values[5]
    ]
}

impl JointTrajectory {
    /// The time-optimal jerk-limited trajectory from `(q0, qd0)` to `target` at rest, all joints
    /// arriving together.
    pub fn plan(
        q0: &[f64; 6],
        qd0: &[f64; 6],
        target: &[f64; 6],
        limits: &MotionLimits,
    ) -> Result<Self, MotionError> {
        let mut otg = Ruckig::<6, ThrowErrorHandler>::new(None, 0.01);
        let mut input = InputParameter::new(None);
        input.current_position = daov(*q0);
        input.current_velocity = daov(*qd0);
        input.target_position = daov(*target);
        input.max_velocity = daov(limits.max_velocity);
        input.max_acceleration = daov(limits.max_acceleration);
        input.max_jerk = daov(limits.max_jerk);
        let mut trajectory = Trajectory::new(None);
        otg.calculate(&input, &mut trajectory)
            .map_err(|e| MotionError(format!("{e:?}")))?;
        Ok(Self {
            trajectory,
            target: *target,
        })
    }

    /// Duration \[s\].
    pub fn duration(&self) -> f64 {
        self.trajectory.get_duration()
    }

    /// The target joints \[rad\].
    pub fn target(&self) -> [f64; 6] {
        self.target
    }

    /// Position \[rad\], velocity \[rad/s\] and acceleration \[rad/s²\] at time `t`
    /// (held at the end).
    pub fn sample(&self, t: f64) -> ([f64; 6], [f64; 6], [f64; 6]) {
        let mut p = daov([0.0; 6]);
        let mut v = daov([0.0; 6]);
        let mut a = daov([0.0; 6]);
        self.trajectory.at_time(
            t.clamp(0.0, self.duration()),
            &mut Some(&mut p),
            &mut Some(&mut v),
            &mut Some(&mut a),
            &mut None,
            &mut None,
        );
        (
            std::array::from_fn(|i| p[i]),
            std::array::from_fn(|i| v[i]),
            std::array::from_fn(|i| a[i]),
        )
    }
}

/// The joint part of a velocity action that follows a reference from `q_now` to `q_next` \[rad\]
/// over one env step of `dt` \[s\]: the reference's velocity plus `gain` \[1/s\] times the measured
/// joints' (`q`) lag behind `q_now`, in units of the action's `scale` \[rad/s\], each clipped to
/// [−1, 1]. The scripts' one tracking law.
pub fn tracking_action(
    q_now: &[f64; 6],
    q_next: &[f64; 6],
    q: &[f64; 6],
    gain: f64,
    dt: f64,
    scale: f64,
) -> [f64; 6] {
    std::array::from_fn(|i| {
        let feedforward = (q_next[i] - q_now[i]) / dt;
        let feedback = gain * (q_now[i] - q[i]);
        ((feedforward + feedback) / scale).clamp(-1.0, 1.0)
    })
}
