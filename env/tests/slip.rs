//! Physical facts behind the contact family `heavy_slippery`: two pads squeezing with force F
//! \[N\] each hold a cube of mass m \[kg\] while their friction can carry its weight,
//! 2·F·μ ≥ m·g, with μ the pad–cube friction coefficient (rapier's default rule averages the
//! pad's and the cube's coefficients). A cube too heavy for that slips out of the grip as the
//! gripper lifts and stays on the table; a harder squeeze lifts the same cube.
//! Measured here (servo arm, scenario 0): at 1.75× the cube slips under 2 mm over a 10 cm lift,
//! at 0.51× it stays on the table, at 1.22× (12 N) it rises 8.9 cm of the gripper's 10.

mod common;

use fairgrasp_env::{ArmSimulation, EnvConfig, TaskEnv};

const G: f64 = 9.81;

/// What happened when the gripper closed on the cube and then rose 10 cm.
struct Lift {
    /// Both pads touched the cube once closed.
    pads_touched: bool,
    /// How far the cube rose \[m\].
    cube_rise: f64,
    /// How far the TCP rose \[m\].
    tcp_rise: f64,
}

fn config(cube_mass: f64, cube_friction: f64, force: f64) -> EnvConfig {
    let mut cfg = common::config(ArmSimulation::Servo);
    cfg.scene.cube_mass = cube_mass;
    cfg.scene.cube_friction = cube_friction;
    cfg.gripper.force = force;
    cfg
}

/// The friction force the grip can carry over the cube's weight, for `cfg`.
fn capacity_over_weight(cfg: &EnvConfig) -> f64 {
    let mu = 0.5 * (cfg.gripper.pad_friction + cfg.scene.cube_friction);
    2.0 * cfg.gripper.force * mu / (cfg.scene.cube_mass * G)
}

fn grasp_and_lift(cfg: EnvConfig) -> Lift {
    let mut env = TaskEnv::new(cfg).unwrap();
    env.reset(0).unwrap();
    let (grasp, above) = common::grasp_targets(&env);
    common::drive(&mut env, above, -1.0, 50);
    common::drive(&mut env, grasp, -1.0, 30);
    let closed = common::drive(&mut env, grasp, 1.0, 15);
    let pads_touched = closed.obs.pad_contact[0] && closed.obs.pad_contact[1];
    let cube_start = env.object_in_base().xyz()[2];
    let tcp_start = env.tcp_in_base().xyz()[2];
    common::drive(&mut env, above, 1.0, 50);
    let cube_rise = env.object_in_base().xyz()[2] - cube_start;
    let tcp_rise = env.tcp_in_base().xyz()[2] - tcp_start;
    assert!(
        cube_rise.is_finite() && tcp_rise.is_finite(),
        "NaN in the lift: cube {cube_rise}, tcp {tcp_rise}"
    );
    Lift {
        pads_touched,
        cube_rise,
        tcp_rise,
    }
}

#[test]
fn a_cube_the_grip_can_carry_1_75_times_over_is_lifted_with_the_gripper() {
    // 0.35 kg, μ 0.6 between pad and cube, 5 N per finger: 6.0 N of friction for 3.4 N.
    let cfg = config(0.35, 0.4, 5.0);
    let ratio = capacity_over_weight(&cfg);
    assert!((1.7..1.8).contains(&ratio), "{ratio}");
    let lift = grasp_and_lift(cfg);
    assert!(lift.pads_touched, "the pads never closed on the cube");
    assert!(lift.tcp_rise > 0.095, "TCP rose {:.4} m", lift.tcp_rise);
    // Slip in the grip under 2 mm over the 10 cm lift.
    assert!(
        lift.tcp_rise - lift.cube_rise < 0.002,
        "the cube slipped {:.4} m (cube rose {:.4}, TCP {:.4})",
        lift.tcp_rise - lift.cube_rise,
        lift.cube_rise,
        lift.tcp_rise
    );
}

#[test]
fn a_cube_twice_as_heavy_as_the_grip_carries_slips_out_and_stays_on_the_table() {
    // 1.0 kg, μ 0.5 between pad and cube, 5 N per finger: 5.0 N of friction for 9.8 N.
    let cfg = config(1.0, 0.2, 5.0);
    let ratio = capacity_over_weight(&cfg);
    assert!((0.5..0.52).contains(&ratio), "{ratio}");
    let lift = grasp_and_lift(cfg);
    assert!(lift.pads_touched, "the pads never closed on the cube");
    assert!(lift.tcp_rise > 0.095, "TCP rose {:.4} m", lift.tcp_rise);
    // The cube rises under 1 cm while the gripper rises 10 cm.
    assert!(
        lift.cube_rise < 0.01,
        "the cube rose {:.4} m with the gripper",
        lift.cube_rise
    );
}

#[test]
fn the_same_heavy_cube_is_lifted_by_a_12_newton_squeeze() {
    // 1.0 kg, μ 0.5, 12 N per finger: 12 N of friction for 9.8 N.
    let cfg = config(1.0, 0.2, 12.0);
    assert!(capacity_over_weight(&cfg) > 1.2);
    let lift = grasp_and_lift(cfg);
    assert!(lift.pads_touched, "the pads never closed on the cube");
    // Lifted with the gripper: at least 8 of its 10 cm (it creeps 1.2 cm in the grip at 1.2×
    // its weight, against staying on the table at 5 N).
    assert!(
        lift.cube_rise > 0.08,
        "the cube rose only {:.4} m (TCP {:.4})",
        lift.cube_rise,
        lift.tcp_rise
    );
}
