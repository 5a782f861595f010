//! The place task's rules, pure functions of the state: the cube seated in the fixture's pocket,
//! released, the arm clear. Its settings are `[task.place]` ([`crate::config::PlaceConfig`]).

use crate::config::PlaceConfig;
use crate::task::state::{PlaceFacts, TaskState, distance_via_object, released_and_clear};

/// Seated: the cube's centre inside the pocket, its bottom on the table (the pocket's floor)
/// and standing on a face: then it is between the walls, which a cube on the floor can only be
/// inside.
pub fn is_seated(f: &PlaceFacts, object_size: f64, p: &PlaceConfig) -> bool {
    let half = p.pocket_half_side(object_size);
    f.offset_in_fixture.iter().all(|o| o.abs() < half)
        && f.bottom_above_table <= p.seated_height
        && f.tilt <= p.max_tilt
}

/// Released and clear: neither pad on the cube and the TCP at least `clear_height` above its
/// top.
pub fn is_clear(s: &TaskState, p: &PlaceConfig) -> bool {
    released_and_clear(s, p.clear_height)
}

/// The place task's success: seated, released, the arm clear.
pub fn is_placed(s: &TaskState, f: &PlaceFacts, p: &PlaceConfig) -> bool {
    is_seated(f, s.object_size, p) && is_clear(s, p)
}

/// How far the task still has to go \[m\]: the TCP to the cube, plus the cube to where it sits
/// seated in the pocket (what the distance reward pays for in this task).
pub fn distance_to_go(s: &TaskState, f: &PlaceFacts) -> f64 {
    distance_via_object(s, f, 0.5 * s.object_size)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(tcp_above: f64, pads: bool) -> TaskState {
        TaskState {
            object: [0.3, 0.2, 0.625],
            object_rest_z: 0.625,
            tcp: [0.3, 0.2, 0.625 + tcp_above],
            pad_contact: [pads, false],
            gripper_opening: 0.085,
            object_size: 0.05,
            table_height: 0.6,
            object_xy_from_table_centre: [0.3, 0.2],
            table_half_size: [0.6, 0.6],
            place: None,
        }
    }

    fn facts(offset: f64, bottom: f64, tilt: f64) -> PlaceFacts {
        PlaceFacts {
            offset_in_fixture: [offset, 0.0],
            bottom_above_table: bottom,
            tilt,
            fixture: [0.3, 0.2, 0.6],
        }
    }

    #[test]
    fn seated_means_inside_the_pocket_on_its_floor_and_upright() {
        let p = PlaceConfig::default();
        assert!(is_seated(&facts(0.0015, 0.0005, 0.01), 0.05, &p));
        // Centre beyond the pocket's half side (27 mm): on the rim or beside the fixture.
        assert!(!is_seated(&facts(0.028, 0.0005, 0.0), 0.05, &p));
        // Resting on the walls, 10 mm up.
        assert!(!is_seated(&facts(0.0, 0.010, 0.0), 0.05, &p));
        // Leaning on a wall.
        assert!(!is_seated(&facts(0.0, 0.001, 0.2), 0.05, &p));
        // Wedged across the pocket: one bottom edge on the floor, leaning 4.5° on the far wall
        // (the most a 50 mm cube leans in 54 mm), corner inside, bottom on the floor.
        assert!(!is_seated(
            &facts(0.002, 0.0005, 4.5f64.to_radians()),
            0.05,
            &p
        ));
    }

    #[test]
    fn placed_needs_the_gripper_released_and_the_arm_clear() {
        let p = PlaceConfig::default();
        let f = facts(0.0, 0.0005, 0.0);
        assert!(is_placed(&state(0.06, false), &f, &p));
        assert!(!is_placed(&state(0.06, true), &f, &p), "a pad still on it");
        assert!(
            !is_placed(&state(0.04, false), &f, &p),
            "TCP 1.5 cm above the top"
        );
    }
}
