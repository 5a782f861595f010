//! The state a step is judged on ([`TaskState`]), in the world frame.

/// The facts the task is judged on, all in the world frame \[m\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaskState {
    /// Object centre.
    pub object: [f64; 3],
    /// Object centre height at rest, before the episode.
    pub object_rest_z: f64,
    /// TCP position.
    pub tcp: [f64; 3],
    /// Left and right pads touching the object.
    pub pad_contact: [bool; 2],
    /// Distance between the pads' inner faces \[m\].
    pub gripper_opening: f64,
    /// The object's edge length \[m\].
    pub object_size: f64,
    /// Table top height.
    pub table_height: f64,
    /// Horizontal distance of the object from the table centre, per axis, and the half sizes.
    pub object_xy_from_table_centre: [f64; 2],
    pub table_half_size: [f64; 2],
    /// The place task's facts (`None` for the lift task).
    pub place: Option<PlaceFacts>,
}

/// Distance from the TCP to the object centre \[m\].
pub fn tcp_object_distance(s: &TaskState) -> f64 {
    (0..3)
        .map(|i| (s.object[i] - s.tcp[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// How far a task that carries the cube onto or into its fixture still has to go, world \[m\]:
/// the TCP's distance to the object plus the object's to its seat, the point
/// `centre_above_fixture` \[m\] above the fixture's origin (`f.fixture`) where the task sets
/// its centre down.
pub fn distance_via_object(s: &TaskState, f: &PlaceFacts, centre_above_fixture: f64) -> f64 {
    let seat = [
        f.fixture[0],
        f.fixture[1],
        f.fixture[2] + centre_above_fixture,
    ];
    let to = |a: [f64; 3], b: [f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
    to(s.tcp, s.object) + to(s.object, seat)
}

/// Released and clear: neither pad on the object and the TCP at least `clear_height` \[m\]
/// above its top (how a task that sets the cube down ends: place, stack).
pub fn released_and_clear(s: &TaskState, clear_height: f64) -> bool {
    let top = s.object[2] + 0.5 * s.object_size;
    !s.pad_contact[0] && !s.pad_contact[1] && s.tcp[2] - top >= clear_height
}

/// The facts about the cube and the fixture a step of a task with a fixture (place, stack) is
/// judged on (world frame, \[m\]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaceFacts {
    /// The cube's centre in the fixture frame (x, y along its walls) \[m\].
    pub offset_in_fixture: [f64; 2],
    /// The cube's lowest corner above the table top \[m\].
    pub bottom_above_table: f64,
    /// The cube's tilt from standing on a face \[rad\].
    pub tilt: f64,
    /// The fixture's centre on the table top, world \[m\].
    pub fixture: [f64; 3],
}
