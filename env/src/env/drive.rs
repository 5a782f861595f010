//! How the arm is driven through one env step: one joint-velocity command for every substep (an
//! [`Action`](crate::env::step::Action)) or a servo stream of one setpoint per substep, and the
//! check of such a stream.

use crate::env::step::{EnvError, ServoSetpoint};

/// Gain of a servo step's feedback on the joints' distance from the setpoint \[1/s\]: a tenth of
/// the error corrected per 1/240 s substep, the feedforward velocity doing the rest.
const SERVO_GAIN: f64 = 24.0;

/// How the arm moves during one env step.
#[derive(Clone, Copy)]
pub(crate) enum Drive<'a> {
    /// One joint-velocity command \[rad/s\] for every substep (an action).
    Velocity([f64; 6]),
    /// A setpoint per substep (a servo stream).
    Servo(&'a [ServoSetpoint]),
}

impl Drive<'_> {
    /// The joint-velocity command \[rad/s\] of substep `j`, from the reference `q_ref` \[rad\]:
    /// the action's, or the setpoint's velocity plus [`SERVO_GAIN`] times the distance to its
    /// position. The robot's rate limiter still applies.
    pub(crate) fn command(&self, j: usize, q_ref: &[f64; 6]) -> [f64; 6] {
        match self {
            Drive::Velocity(command) => *command,
            Drive::Servo(setpoints) => {
                let s = &setpoints[j];
                std::array::from_fn(|i| s.velocity[i] + SERVO_GAIN * (s.position[i] - q_ref[i]))
            }
        }
    }

    /// The gripper command of substep `j`, if this drive sets one per substep.
    pub(crate) fn gripper(&self, j: usize) -> Option<f64> {
        match self {
            Drive::Velocity(_) => None,
            Drive::Servo(setpoints) => Some(setpoints[j].gripper),
        }
    }
}

/// Refuses a servo stream that is not one setpoint per substep (`expected` of them) or holds a
/// non-finite number, naming the substep and the value.
pub(crate) fn check_setpoints(
    setpoints: &[ServoSetpoint],
    expected: usize,
) -> Result<(), EnvError> {
    if setpoints.len() != expected {
        let got = setpoints.len();
        return Err(EnvError::SetpointCount { expected, got });
    }
    for (substep, s) in setpoints.iter().enumerate() {
        let what = if s.position.iter().any(|v| !v.is_finite()) {
            format!("position {:?}", s.position)
        } else if s.velocity.iter().any(|v| !v.is_finite()) {
            format!("velocity {:?}", s.velocity)
        } else if !s.gripper.is_finite() {
            format!("gripper {}", s.gripper)
        } else {
            continue;
        };
        return Err(EnvError::NonFiniteSetpoint { substep, what });
    }
    Ok(())
}
