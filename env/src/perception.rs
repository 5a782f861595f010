//! The perception model: what a policy observes of the object, given the truth.
//!
//! The truth (the object's pose in the world) is for the task and for oracles; policies see
//! only what this model reports. A new way of seeing (a miscalibrated camera, a wrist camera
//! that improves up close) is a change here and in the scenario that draws its parameters, not
//! in the env's step.

use fairgrasp_kinematics::Pose;

use crate::mount::Mount;
use crate::randomize::Scenario;

/// The object as a policy observes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObservedObject {
    /// Object centre in `base_link` [m].
    pub position: [f64; 3],
    /// Object yaw about the world vertical, relative to the base's heading [rad].
    pub yaw: f64,
}

/// What is observed of an object whose true pose in `base_link` is `truth`, in the episode
/// `scenario` (its perception errors), on `mount`. With no scenario (before the first reset),
/// the truth.
pub fn observe_object(mount: &Mount, truth: &Pose, scenario: Option<&Scenario>) -> ObservedObject {
    let (position_error, yaw_error) = scenario.map_or(([0.0; 3], 0.0), |s| {
        (s.observed_position_error, s.observed_yaw_error)
    });
    // Perception errors are drawn in the table frame (on the table plane).
    let error = mount.table_in_base.transform_vector(position_error);
    let p = truth.xyz();
    ObservedObject {
        position: [p[0] + error[0], p[1] + error[1], p[2] + error[2]],
        yaw: mount.yaw_on_table(truth) + yaw_error,
    }
}
