//! Free-space steps (`physics.free_space`): the same motion as full physics while nothing can
//! touch the object, a seamless hand-over to physics, and a deterministic switch.

mod common;

use fairgrasp_env::env::free_space::joint_reach;
use fairgrasp_env::task::Failure;
use fairgrasp_env::{Action, ArmSimulation, EnvConfig, Step, TaskEnv};

fn env_with(free_space: bool) -> TaskEnv {
    let mut config = common::config(ArmSimulation::Servo);
    config.physics.free_space = free_space;
    TaskEnv::new(config).unwrap()
}

/// Largest difference between the two fingers' travels \[m\].
fn finger_gap(a: &TaskEnv, b: &TaskEnv) -> f64 {
    (0..2)
        .map(|f| (a.finger_travel()[f] - b.finger_travel()[f]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn free_space_steps_move_arm_and_fingers_as_full_physics_does() {
    let (mut free, mut full) = (env_with(true), env_with(false));
    free.reset(3).unwrap();
    full.reset(3).unwrap();
    let mut free_steps = 0;
    let mut worst_finger = 0.0_f64;
    // Swing j1 back and forth high above the cube while closing and opening the gripper.
    for k in 0..60 {
        let swing = if (k / 15) % 2 == 0 { 0.8 } else { -0.8 };
        let grip = if (k / 6) % 2 == 0 { 1.0 } else { -1.0 };
        let action = Action([swing, 0.0, 0.0, 0.0, 0.0, 0.0, grip]);
        let (a, b) = (free.step(&action).unwrap(), full.step(&action).unwrap());
        free_steps += usize::from(!a.info.simulated);
        assert!(b.info.simulated, "free_space = false must always simulate");
        // The servo arm integrates the same reference either way: identical joints.
        assert_eq!(free.joints(), full.joints(), "step {k}");
        worst_finger = worst_finger.max(finger_gap(&free, &full));
        assert_eq!(a.info.failure, b.info.failure, "step {k}");
        assert_eq!(a.terminated, b.terminated, "step {k}");
    }
    eprintln!("free steps {free_steps}/60, worst finger travel gap {worst_finger:.6} m");
    assert!(free_steps >= 55, "only {free_steps} of 60 steps were free");
    assert!(
        worst_finger < 5e-4,
        "the finger drive in free space drifted {worst_finger:.6} m from rapier's"
    );
    // The object was never touched: it is exactly where full physics left it, within 0.1 mm.
    let (p, q) = (free.object_in_base().xyz(), full.object_in_base().xyz());
    let moved = (0..3).map(|i| (p[i] - q[i]).powi(2)).sum::<f64>().sqrt();
    assert!(moved < 1e-4, "object differs by {moved} m");
}

/// Rapier does not compute the servo arm's link, palm and table pairs (kinematic and fixed
/// bodies): a step that runs physics checks them on the exact shapes, as a free-space step
/// does. Driving links into the table and into each other must then end both envs at the same
/// step with the same pair, whichever kind of step found it, named in the one order (table
/// first, then from the base out).
#[test]
fn links_driven_into_the_table_or_each_other_collide_alike_with_and_without_physics() {
    let cases = [
        ([0.0, 1.0, 0.0, 0.0, 0.0, 0.0], "table", "upperarm_link"),
        ([0.0, 1.0, 1.0, 0.0, 0.0, 0.0], "table", "wrist2_link"),
        ([0.0, 0.0, -1.0, 0.0, 0.0, 0.0], "upperarm_link", "palm"),
        (
            [0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
            "upperarm_link",
            "wrist1_link",
        ),
        (
            [0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
            "forearm_link",
            "wrist2_link",
        ),
    ];
    for (joints, first, second) in cases {
        let (mut free, mut full) = (env_with(true), env_with(false));
        free.reset(3).unwrap();
        full.reset(3).unwrap();
        let action = Action([
            joints[0], joints[1], joints[2], joints[3], joints[4], 0.0, -1.0,
        ]);
        let ending = (0..200).find_map(|k| {
            let (a, b) = (free.step(&action).unwrap(), full.step(&action).unwrap());
            assert!(b.info.simulated, "{joints:?} step {k}");
            assert_eq!(a.info.failure, b.info.failure, "{joints:?} step {k}");
            assert_eq!(a.info.collision_depth_m, b.info.collision_depth_m);
            b.terminated
                .then_some((b.info.failure, b.info.collision_depth_m))
        });
        let Some((Some(Failure::Collision(a, b)), Some(depth))) = ending else {
            panic!("{joints:?}: expected a collision, got {ending:?}");
        };
        assert_eq!((a.as_str(), b.as_str()), (first, second), "{joints:?}");
        assert!(depth > 0.0 && depth < 0.03, "{joints:?}: {depth} m");
    }
}

/// Drives a top-down grasp and lift; returns every step.
fn grasp_and_lift(env: &mut TaskEnv, seed: u64) -> Vec<Step> {
    env.reset(seed).unwrap();
    let (grasp, above) = common::grasp_targets(env);
    let mut steps = Vec::new();
    for (target, grip, n) in [
        (above, -1.0, 40),
        (grasp, -1.0, 30),
        (grasp, 1.0, 12),
        (above, 1.0, 30),
    ] {
        for _ in 0..n {
            let action = common::toward(env, target, grip);
            steps.push(env.step(&action).unwrap());
        }
    }
    steps
}

#[test]
fn the_hand_over_to_physics_injects_no_motion_and_the_grasp_matches_full_physics() {
    let (mut free, mut full) = (env_with(true), env_with(false));
    let a = grasp_and_lift(&mut free, 5);
    let b = grasp_and_lift(&mut full, 5);
    let free_steps = a.iter().filter(|s| !s.info.simulated).count();
    let first_simulated = a.iter().position(|s| s.info.simulated).unwrap();
    eprintln!("{free_steps} free steps; first simulated step {first_simulated}");
    assert!(
        free_steps >= 20,
        "only {free_steps} free steps on the approach"
    );
    assert!(first_simulated > 0, "the approach started with physics");
    // The approach is free until the gripper nears the cube, then physics takes over: the
    // lift is simulated.
    assert!(a.last().unwrap().info.simulated);
    let lifted = |steps: &[Step]| steps.last().unwrap().obs.pad_contact == [true, true];
    assert!(lifted(&a) && lifted(&b), "the cube was not held at the end");
    // Same joints all along (the servo arm), and the cube follows the same path within 0.5 mm.
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert_eq!(x.obs.joints, y.obs.joints, "step {k}");
        let gap = (0..3)
            .map(|i| (x.obs.object_rel_tcp[i] - y.obs.object_rel_tcp[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(gap < 5e-4, "step {k}: the cube differs by {gap} m");
        assert!(
            (x.obs.gripper_opening - y.obs.gripper_opening).abs() < 1e-3,
            "step {k}: gripper opening {} vs {}",
            x.obs.gripper_opening,
            y.obs.gripper_opening
        );
    }
}

#[test]
fn the_free_space_switch_is_deterministic_seed_replays_are_bit_identical() {
    let run = || {
        let mut env = env_with(true);
        grasp_and_lift(&mut env, 11)
            .into_iter()
            .map(|s| (s.obs.to_array(), s.reward.to_bits(), s.info.simulated))
            .collect::<Vec<_>>()
    };
    let (a, b) = (run(), run());
    assert!(a.iter().any(|s| !s.2) && a.iter().any(|s| s.2));
    assert_eq!(a, b);
}

#[test]
fn the_multibody_arm_always_simulates() {
    let mut config = EnvConfig::default();
    config.arm.model = ArmSimulation::Multibody;
    let mut env = TaskEnv::new(config).unwrap();
    env.reset(0).unwrap();
    for _ in 0..5 {
        assert!(env.step(&Action::hold_open()).unwrap().info.simulated);
    }
}

#[test]
fn every_joint_reach_bounds_the_distance_of_the_points_it_moves() {
    let model = fairgrasp_kinematics::ArmKind::Fr3.model();
    let reach = joint_reach(&model);
    // The TCP is moved by every joint: its distance from each joint's axis origin is within
    // the bound at any joint angles.
    for k in 0..200 {
        let q: [f64; 6] = std::array::from_fn(|i| ((k * 7 + i * 13) % 17) as f64 * 0.37 - 3.0);
        let tcp = model.fk_tcp(&q).xyz();
        let poses = model.link_poses(&q);
        for i in 0..6 {
            let o = poses[i + 1].translation.vector;
            let d =
                ((tcp[0] - o.x).powi(2) + (tcp[1] - o.y).powi(2) + (tcp[2] - o.z).powi(2)).sqrt();
            assert!(
                d <= reach[i],
                "joint {i}: TCP {d} m away, bound {}",
                reach[i]
            );
        }
    }
    assert!(reach.windows(2).all(|w| w[0] >= w[1]), "{reach:?}");
    assert!(reach[5] < 0.4 && reach[0] < 1.5, "{reach:?}");
}

/// `task.terminate_on_self_collision` in a training env (`terminate_on_collision = false`): the
/// arm driven into itself ends the episode at the collision, the arm driven into the table goes
/// on through it; without the option neither ends.
#[test]
fn only_a_self_collision_ends_a_training_episode_when_the_task_says_so() {
    let into_table = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0];
    let into_itself = [0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0];
    for ends_on_self in [false, true] {
        let mut config = common::config(ArmSimulation::Servo);
        config.task.terminate_on_collision = false;
        config.task.terminate_on_self_collision = ends_on_self;
        for (action, self_collision) in [(into_table, false), (into_itself, true)] {
            let mut env = TaskEnv::new(config.clone()).unwrap();
            env.reset(3).unwrap();
            let mut step = || env.step(&Action(action)).unwrap();
            let hit = (0..200)
                .map(|_| step())
                .find(|s| s.terminated || s.info.failure.is_some())
                .unwrap_or_else(|| panic!("{action:?}: no collision in 200 steps"));
            let Some(Failure::Collision(a, _)) = &hit.info.failure else {
                panic!(
                    "{action:?}: expected a collision, got {:?}",
                    hit.info.failure
                );
            };
            assert_eq!(
                a != "table",
                self_collision,
                "{action:?}: {:?}",
                hit.info.failure
            );
            let ends_here = ends_on_self && self_collision;
            assert_eq!(hit.terminated, ends_here, "{action:?} {ends_on_self}");
            if !ends_here {
                assert!(!step().terminated, "{action:?}: the episode goes on");
            }
        }
    }
}
