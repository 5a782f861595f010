//! What the wrist camera sees of the cube at a step.

use fairgrasp_kinematics::Pose;

use crate::cell::mount::Mount;
use crate::scenario::perception::{ObservedObject, true_object};
use crate::scenario::wrist_camera::settings::WristCamera;

/// What the wrist camera `camera` (None: there is none) sees of an object whose true pose in
/// `base_link` is `truth`, with the TCP at `tcp` [m, `base_link`]: the truth, once the TCP is
/// within the camera's range of the object's centre; otherwise nothing.
pub fn wrist_view(
    camera: Option<&WristCamera>,
    mount: &Mount,
    truth: &Pose,
    tcp: [f64; 3],
) -> Option<ObservedObject> {
    let range = camera?.range;
    let centre = truth.xyz();
    let distance = (0..3)
        .map(|i| (centre[i] - tcp[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    (distance <= range).then(|| true_object(mount, truth))
}
