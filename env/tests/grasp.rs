//! Physical facts about grasping, in both arm models: the cube is held, does not slip, and the
//! pads do not sink into it.

mod common;

use fairgrasp_env::{ArmSimulation, TaskEnv};

fn lift_and_hold(arm: ArmSimulation) {
    let mut env = TaskEnv::new(common::config(arm)).unwrap();
    env.reset(0).unwrap();
    let (grasp, above) = common::grasp_targets(&env);
    common::drive(&mut env, above, -1.0, 50);
    common::drive(&mut env, grasp, -1.0, 30);
    common::drive(&mut env, grasp, 1.0, 15);
    let rest_z = env.object_in_base().xyz()[2];
    common::drive(&mut env, above, 1.0, 50);
    let lifted = env.object_in_base().xyz()[2] - rest_z;
    assert!(lifted > 0.095, "{arm:?}: lifted only {lifted:.4} m");

    // Hold 2 s (24 env steps of 1/12 s): the cube stays put relative to the TCP.
    let start = env
        .tcp_in_base()
        .inverse()
        .transform_point(env.object_in_base().xyz());
    let mut worst_penetration = 0.0_f64;
    for _ in 0..24 {
        let step = env.step(&common::toward(&env, above, 1.0)).unwrap();
        assert!(
            step.obs.pad_contact[0] && step.obs.pad_contact[1],
            "{arm:?}: a pad lost the cube"
        );
        assert!(
            step.info.failure.is_none(),
            "{arm:?}: {:?}",
            step.info.failure
        );
        worst_penetration = worst_penetration.max(env.contacts().pad_penetration);
    }
    let end = env
        .tcp_in_base()
        .inverse()
        .transform_point(env.object_in_base().xyz());
    let moved = (0..3)
        .map(|i| (end[i] - start[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    eprintln!(
        "{arm:?}: moved {moved:.5} m, pad penetration {worst_penetration:.5} m, lifted {lifted:.4} m"
    );
    assert!(
        moved <= 0.002,
        "{arm:?}: the cube moved {moved:.5} m relative to the TCP: {start:?} -> {end:?}"
    );
    assert!(
        worst_penetration <= 0.002,
        "{arm:?}: pads sank {worst_penetration:.5} m into the cube"
    );
    // Held between the pads: the cube centre is within 3 mm of the TCP across the fingers.
    assert!(
        end[0].abs() < 0.003,
        "{arm:?}: off centre by {:.4} m",
        end[0]
    );
}

#[test]
fn servo_arm_lifts_the_cube_10_cm_and_holds_it_2_s_without_slip_or_sinking() {
    lift_and_hold(ArmSimulation::Servo);
}

#[test]
fn multibody_arm_lifts_the_cube_10_cm_and_holds_it_2_s_without_slip_or_sinking() {
    lift_and_hold(ArmSimulation::Multibody);
}

#[test]
fn open_fingers_let_go_and_the_cube_falls_back_to_the_table() {
    let mut env = TaskEnv::new(common::config(ArmSimulation::Servo)).unwrap();
    env.reset(0).unwrap();
    let rest_z = env.object_in_base().xyz()[2];
    let (grasp, above) = common::grasp_targets(&env);
    common::drive(&mut env, above, -1.0, 50);
    common::drive(&mut env, grasp, -1.0, 30);
    common::drive(&mut env, grasp, 1.0, 15);
    common::drive(&mut env, above, 1.0, 40);
    common::drive(&mut env, above, -1.0, 24);
    let z = env.object_in_base().xyz()[2];
    assert!(
        (z - rest_z).abs() < 0.01,
        "the cube did not fall back: {z:.4} vs rest {rest_z:.4}"
    );
}
