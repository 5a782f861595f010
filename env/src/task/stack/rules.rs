//! The stack task's rules, pure functions of the state: the held cube resting squarely on the
//! second cube, released, the arm clear. Its settings are `[task.stack]` ([`StackConfig`]). The
//! facts are the fixture's ([`PlaceFacts`]): the second cube is the stack task's fixture, its
//! origin on the table top under the cube's centre.

use crate::task::stack::settings::StackConfig;
use crate::task::state::{PlaceFacts, TaskState, distance_via_object, released_and_clear};

/// Stacked: the cube's centre within `max_offset` of the second cube's along each of its faces,
/// its bottom on the second cube's top (not more than `max_gap` above it, and not sunk below it
/// by more: it cannot be beside it), standing on a face.
pub fn is_stacked(f: &PlaceFacts, object_size: f64, c: &StackConfig) -> bool {
    f.offset_in_fixture.iter().all(|o| o.abs() <= c.max_offset)
        && (f.bottom_above_table - object_size).abs() <= c.max_gap
        && f.tilt <= c.max_tilt
}

/// The stack task's success: stacked, released, the arm clear.
pub fn is_success(s: &TaskState, f: &PlaceFacts, c: &StackConfig) -> bool {
    is_stacked(f, s.object_size, c) && released_and_clear(s, c.clear_height)
}

/// How far the task still has to go \[m\]: the TCP to the cube, plus the cube to where it sits
/// stacked, its centre one and a half edges above the second cube's footprint.
pub fn distance_to_go(s: &TaskState, f: &PlaceFacts) -> f64 {
    distance_via_object(s, f, 1.5 * s.object_size)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn facts(offset: f64, bottom: f64, tilt: f64) -> PlaceFacts {
        PlaceFacts {
            offset_in_fixture: [offset, -0.5 * offset],
            bottom_above_table: bottom,
            tilt,
            fixture: [0.3, 0.2, 0.6],
        }
    }

    #[test]
    fn stacked_means_on_the_second_cubes_top_centred_and_upright() {
        let c = StackConfig::default();
        let size = 0.05;
        assert!(is_stacked(&facts(0.004, 0.0505, 0.01), size, &c));
        // Off centre by 6 mm: overhanging more than the criterion allows.
        assert!(!is_stacked(&facts(0.006, 0.0505, 0.0), size, &c));
        // On the table beside it (its bottom 5 cm below the top).
        assert!(!is_stacked(&facts(0.0, 0.0, 0.0), size, &c));
        // Still held 5 mm above it.
        assert!(!is_stacked(&facts(0.0, 0.055, 0.0), size, &c));
        // Leaning on an edge.
        assert!(!is_stacked(&facts(0.0, 0.051, 0.2), size, &c));
    }

    #[test]
    fn the_distance_to_go_is_zero_only_held_at_the_stacked_pose() {
        let f = facts(0.0, 0.05, 0.0);
        let stacked = [0.3, 0.2, 0.6 + 0.075];
        let at = |object: [f64; 3], tcp: [f64; 3]| TaskState {
            object,
            object_rest_z: 0.625,
            tcp,
            pad_contact: [true, true],
            gripper_opening: 0.05,
            object_size: 0.05,
            table_height: 0.6,
            object_xy_from_table_centre: [0.3, 0.2],
            table_half_size: [0.6, 0.6],
            place: Some(f),
        };
        assert!(distance_to_go(&at(stacked, stacked), &f) < 1e-12);
        let on_table = [0.4, 0.2, 0.625];
        let d = distance_to_go(&at(on_table, on_table), &f);
        assert!(
            (d - (0.1f64.powi(2) + 0.05f64.powi(2)).sqrt()).abs() < 1e-12,
            "{d}"
        );
    }
}
