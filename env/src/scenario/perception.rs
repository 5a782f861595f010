//! The perception model: what a policy observes of the object, given the truth.
//!
//! The truth (the object's pose in the world) is for the task and for oracles; policies see
//! only what this model reports. A new way of seeing (a miscalibrated camera, a wrist camera
//! that improves up close) is a change here and in the scenario that draws its parameters, not
//! in the env's step.
//!
//! Order: the camera's calibration error (a rigid transform of the table frame,
//! [`crate::scenario::camera_offset::CameraOffset`]) moves the true pose first; the episode's perception noise
//! is added to the result.

use fairgrasp_kinematics::Pose;

use crate::cell::mount::Mount;
use crate::scenario::Scenario;

/// The object as a policy observes it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ObservedObject {
    /// Object centre in `base_link` \[m\].
    pub position: [f64; 3],
    /// Object yaw about the world vertical, relative to the base's heading \[rad\].
    pub yaw: f64,
}

/// What is observed of an object whose true pose in `base_link` is `truth`, in the episode
/// `scenario` (its camera error and perception noise), on `mount`. With no scenario (before the
/// first reset), the truth.
pub fn observe_object(mount: &Mount, truth: &Pose, scenario: Option<&Scenario>) -> ObservedObject {
    let (position_error, yaw_error) = scenario.map_or(([0.0; 3], 0.0), |s| {
        (s.observed_position_error, s.observed_yaw_error)
    });
    // The miscalibrated camera sees the pose moved by its error, in the table frame.
    let seen = match scenario.and_then(|s| s.camera_offset) {
        Some(offset) => {
            mount.table_to_base(&offset.in_table().compose(&mount.base_to_table(truth)))
        }
        None => *truth,
    };
    // Perception errors are drawn in the table frame (on the table plane).
    let error = mount.table_in_base.transform_vector(position_error);
    let p = seen.xyz();
    ObservedObject {
        position: [p[0] + error[0], p[1] + error[1], p[2] + error[2]],
        yaw: mount.yaw_on_table(&seen) + yaw_error,
    }
}

/// The truth as an [`ObservedObject`]: what an oracle is given ([`crate::episode::Policy::observe_truth`]).
pub fn true_object(mount: &Mount, truth: &Pose) -> ObservedObject {
    observe_object(mount, truth, None)
}

/// What is known of the place task's fixture whose true pose in `base_link` is `truth`: that
/// pose moved by the scenario's error (`task.place.observed_*_noise`, drawn in the table
/// frame); the truth when the scenario draws none (`fixture` is `None`).
pub fn observe_fixture(
    mount: &Mount,
    truth: &Pose,
    fixture: Option<&crate::scenario::fixture::FixturePose>,
) -> ObservedObject {
    let seen = true_object(mount, truth);
    let Some(f) = fixture else {
        return seen;
    };
    let e = &f.observed_xy_error;
    let error = mount.table_in_base.transform_vector([e[0], e[1], 0.0]);
    ObservedObject {
        position: [0, 1, 2].map(|i| seen.position[i] + error[i]),
        yaw: seen.yaw + f.observed_yaw_error,
    }
}
