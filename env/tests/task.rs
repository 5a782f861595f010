//! Success and reward as pure functions: checked without any physics.

use fairgrasp_env::config::TaskConfig;
use fairgrasp_env::task::{TaskState, is_off_table, is_success, reward, tcp_object_distance};

fn state(object_z: f64, pads: [bool; 2]) -> TaskState {
    TaskState {
        object: [0.3, 0.0, object_z],
        object_rest_z: 0.625,
        tcp: [0.3, 0.0, object_z + 0.002],
        pad_contact: pads,
        gripper_opening: 0.05,
        object_size: 0.05,
        table_height: 0.6,
        object_xy_from_table_centre: [0.3, 0.0],
        table_half_size: [0.6, 0.6],
        place: None,
    }
}

#[test]
fn success_needs_the_lift_and_both_pads() {
    let cfg = TaskConfig::default();
    assert!(is_success(&state(0.656, [true, true]), &cfg));
    assert!(
        !is_success(&state(0.654, [true, true]), &cfg),
        "2.9 cm is not 3 cm"
    );
    assert!(
        !is_success(&state(0.70, [true, false]), &cfg),
        "one pad is not a grasp"
    );
}

#[test]
fn reward_is_sparse_success_collision_or_dense_distance() {
    let cfg = TaskConfig::default();
    let s = state(0.625, [false, false]);
    assert_eq!(reward(&s, true, false, &cfg), 10.0);
    assert_eq!(reward(&s, false, true, &cfg), -1.0);
    let d = tcp_object_distance(&s);
    assert!((d - 0.002).abs() < 1e-12);
    assert!((reward(&s, false, false, &cfg) + 0.005 * 0.002).abs() < 1e-15);
}

#[test]
fn an_object_below_the_table_top_or_past_its_edge_is_off_the_table() {
    assert!(!is_off_table(&state(0.625, [false; 2])));
    assert!(is_off_table(&state(0.55, [false; 2])));
    let mut s = state(0.625, [false; 2]);
    s.object_xy_from_table_centre = [0.61, 0.0];
    assert!(is_off_table(&s));
}

#[test]
fn a_success_after_a_collision_is_void_only_when_the_task_says_so() {
    use fairgrasp_env::task::{Failure, judge, void_success_after_collision};
    let mut cfg = TaskConfig {
        terminate_on_collision: false,
        ..TaskConfig::default()
    };
    let touch = || Some(Failure::Collision("table".into(), "finger_left_pad".into()));
    let resting = state(0.625, [true, true]);
    let lifted = state(0.656, [true, true]);
    for voids in [false, true] {
        cfg.collision_voids_success = voids;
        let mut first = None;
        // A clean episode's success stands either way.
        let clean =
            void_success_after_collision(judge(&lifted, None, &cfg), &mut first, &lifted, &cfg);
        assert!(
            clean.success && clean.terminated && clean.reward == 10.0,
            "{voids}: {clean:?}"
        );
        // The table touched (the episode goes on), then the cube lifted.
        let hit = void_success_after_collision(
            judge(&resting, touch(), &cfg),
            &mut first,
            &resting,
            &cfg,
        );
        assert!(!hit.terminated && hit.failure == touch());
        assert_eq!(first, touch(), "the first collision is kept");
        let after =
            void_success_after_collision(judge(&lifted, None, &cfg), &mut first, &lifted, &cfg);
        if voids {
            assert!(!after.success && after.terminated, "{after:?}");
            assert_eq!(after.failure, touch());
            assert_eq!(after.reward, -1.0);
        } else {
            assert!(
                after.success && after.terminated && after.reward == 10.0,
                "{after:?}"
            );
        }
    }
}

#[test]
fn a_self_collision_is_two_robot_parts_and_only_it_can_end_a_training_episode() {
    use fairgrasp_env::task::{Failure, judge};
    let table = Failure::Collision("table".into(), "finger_left_pad".into());
    let itself = Failure::Collision("upperarm_link".into(), "wrist1_link".into());
    assert!(!table.is_self_collision() && itself.is_self_collision());
    assert!(!Failure::ObjectOffTable.is_self_collision());
    let resting = state(0.625, [false, false]);
    for ends_on_self in [false, true] {
        let cfg = TaskConfig {
            terminate_on_collision: false,
            terminate_on_self_collision: ends_on_self,
            ..TaskConfig::default()
        };
        assert!(!judge(&resting, Some(table.clone()), &cfg).terminated);
        let hit = judge(&resting, Some(itself.clone()), &cfg);
        assert_eq!(hit.terminated, ends_on_self);
        assert_eq!((hit.failure, hit.reward), (Some(itself.clone()), -1.0));
    }
}
