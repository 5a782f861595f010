//! The protective stop: a robot part pressing on the cube or the table harder than
//! `task.protective_stop_force` ends the episode, in both arm models; the field is validated.

mod common;

use fairgrasp_env::config::TaskConfig;
use fairgrasp_env::task::{Failure, TaskState, judge_protective_stop};
use fairgrasp_env::{ArmSimulation, ConfigError, EnvConfig, Step, TaskEnv};

/// The cube centre's height in `world` \[m\].
fn object_world_z(env: &TaskEnv) -> f64 {
    (env.base_in_world().iso * env.object_in_base().iso)
        .translation
        .z
}

/// Closes the gripper above the cube, then drives the closed fingers straight down to the grasp
/// pose (TCP at the cube's centre): the pads land on the cube's top and press it into the table.
/// Returns the last step and how far the cube centre went below its resting height \[m\].
fn press_closed_fingers_onto_the_cube(arm: ArmSimulation, threshold: f64) -> (Step, f64) {
    let mut config = common::config(arm);
    config.task.protective_stop_force = threshold;
    let mut env = TaskEnv::new(config).unwrap();
    env.reset(0).unwrap();
    let rest_z = object_world_z(&env);
    let (grasp, above) = common::grasp_targets(&env);
    common::drive(&mut env, above, -1.0, 50);
    common::drive(&mut env, above, 1.0, 15);
    let mut sink = 0.0_f64;
    for _ in 0..60 {
        let step = env.step(&common::toward(&env, grasp, 1.0)).unwrap();
        sink = sink.max(rest_z - object_world_z(&env));
        if step.terminated || step.truncated {
            return (step, sink);
        }
    }
    let step = env.step(&common::toward(&env, grasp, 1.0)).unwrap();
    (step, sink.max(rest_z - object_world_z(&env)))
}

fn a_press_onto_the_cube_is_stopped(arm: ArmSimulation) {
    let threshold = TaskConfig::default().protective_stop_force;
    let (step, sink) = press_closed_fingers_onto_the_cube(arm, threshold);
    eprintln!(
        "{arm:?}: {:?}, sink {:.2} mm",
        step.info.failure,
        sink * 1e3
    );
    assert!(
        step.terminated && !step.truncated,
        "{arm:?}: {:?}",
        step.info
    );
    assert!(
        !step.info.success,
        "{arm:?}: a protective stop is no success"
    );
    match &step.info.failure {
        Some(Failure::ProtectiveStop {
            robot_part,
            other_part,
            force_n,
        }) => {
            assert!(
                robot_part.contains("finger") || robot_part == "palm",
                "{arm:?}: {robot_part}"
            );
            assert_eq!(other_part, "cube", "{arm:?}");
            assert!(*force_n > threshold, "{arm:?}: {force_n} N");
        }
        other => panic!("{arm:?}: expected a protective stop, got {other:?}"),
    }
    assert_eq!(step.reward, TaskConfig::default().distance.collision);
    assert!(sink < 0.002, "{arm:?}: sank {:.2} mm first", sink * 1e3);

    // Without the stop the same descent drives the cube into the table.
    let (step, sink) = press_closed_fingers_onto_the_cube(arm, 1.0e9);
    eprintln!(
        "{arm:?}, stop off: {:?}, sink {:.2} mm",
        step.info.failure,
        sink * 1e3
    );
    assert!(
        !matches!(step.info.failure, Some(Failure::ProtectiveStop { .. })),
        "{arm:?}"
    );
    assert!(
        sink > 0.002,
        "{arm:?}: without the stop the press should sink the cube more than 2 mm, sank {:.2} mm",
        sink * 1e3
    );
}

#[test]
fn a_servo_arm_pressing_the_cube_is_stopped() {
    a_press_onto_the_cube_is_stopped(ArmSimulation::Servo);
}

#[test]
fn a_multibody_arm_pressing_the_cube_is_stopped() {
    a_press_onto_the_cube_is_stopped(ArmSimulation::Multibody);
}

#[test]
fn a_protective_stop_is_never_a_success_even_when_lifted_and_held() {
    let cfg = TaskConfig::default();
    let lifted_and_held = TaskState {
        object: [0.3, 0.0, 0.70],
        object_rest_z: 0.625,
        tcp: [0.3, 0.0, 0.70],
        pad_contact: [true, true],
        gripper_opening: 0.05,
        object_size: 0.05,
        table_height: 0.6,
        object_xy_from_table_centre: [0.3, 0.0],
        table_half_size: [0.6, 0.6],
        place: None,
    };
    assert!(fairgrasp_env::task::is_success(&lifted_and_held, &cfg));
    let stop = Failure::ProtectiveStop {
        robot_part: "finger_left_pad".into(),
        other_part: "cube".into(),
        force_n: 50.0,
    };
    let j = judge_protective_stop(&lifted_and_held, None, stop.clone(), &cfg);
    assert!(!j.success && j.terminated);
    assert_eq!(j.failure, Some(stop.clone()));
    assert_eq!(j.reward, cfg.distance.collision);

    // A stop whose state is also a collision is reported as the collision, still terminated
    // even when collisions do not end episodes.
    let cfg = TaskConfig {
        terminate_on_collision: false,
        ..TaskConfig::default()
    };
    let collision = Failure::Collision("table".into(), "finger_left_pad".into());
    let j = judge_protective_stop(&lifted_and_held, Some(collision.clone()), stop, &cfg);
    assert!(!j.success && j.terminated);
    assert_eq!(j.failure, Some(collision));
}

#[test]
fn a_finger_hitting_the_table_stops_the_robot_even_without_collision_termination() {
    let mut config = common::config(ArmSimulation::Servo);
    config.task.terminate_on_collision = false;
    let mut env = TaskEnv::new(config).unwrap();
    env.reset(0).unwrap();
    // Beside the cube, 6.5 cm below the grasp pose: the open fingers reach the table first.
    let target = common::beside_and_below_grasp(&env);
    let mut ended = None;
    for _ in 0..150 {
        let step = env.step(&common::toward(&env, target, -1.0)).unwrap();
        if step.terminated || step.truncated {
            ended = Some(step);
            break;
        }
    }
    let step = ended.expect("the press into the table must end the episode");
    assert!(step.terminated && !step.info.success, "{:?}", step.info);
    match step.info.failure {
        // A robot part on the table is a collision, whatever the force.
        Some(Failure::Collision(a, b)) => {
            assert_eq!(a, "table");
            assert!(b.starts_with("finger"), "{b}");
        }
        other => panic!("expected the table collision that stopped the robot, got {other:?}"),
    }
}

#[test]
fn a_bad_threshold_is_refused_naming_the_field_and_value() {
    for bad in [0.0, -5.0, f64::NAN, f64::INFINITY] {
        let mut config = EnvConfig::default();
        config.task.protective_stop_force = bad;
        match config.validate() {
            Err(ConfigError::Invalid { field, value, rule }) => {
                assert_eq!(field, "task.protective_stop_force");
                assert_eq!(value, format!("{bad:?}"));
                // Non-finite values are caught first by the walk over every number.
                let finite_rule = !bad.is_finite() && rule == "must be a finite number";
                assert!(rule.contains("(0, inf) N") || finite_rule, "{rule}");
            }
            other => panic!("{bad}: {other:?}"),
        }
    }
    let e = EnvConfig::from_toml_str("[task]\nprotective_stop_force = -1.0\n").unwrap_err();
    let text = e.to_string();
    assert!(text.contains("task.protective_stop_force = -1.0"), "{text}");
    let ok = EnvConfig::from_toml_str("[task]\nprotective_stop_force = 80.0\n").unwrap();
    assert_eq!(ok.task.protective_stop_force, 80.0);
    assert_eq!(EnvConfig::default().task.protective_stop_force, 35.0);
}
