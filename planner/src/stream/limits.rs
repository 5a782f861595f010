//! What a stream for the FR3's controller must respect: the servo periods its driver accepts,
//! the largest step between samples, and the joint limits ([`StreamLimits`]).

use std::ops::RangeInclusive;

use fairgrasp_kinematics::ArmModel;

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
