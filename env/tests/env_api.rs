//! The Env API's contract: no false collisions, named collision pairs, seeded replay, finite
//! state under random actions, physics faults as truncation, clear errors.

mod common;

use fairgrasp_env::task::Failure;
use fairgrasp_env::{Action, ArmSimulation, EnvConfig, EnvError, TaskEnv};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const ARMS: [ArmSimulation; 2] = [ArmSimulation::Servo, ArmSimulation::Multibody];

fn make_env(arm: ArmSimulation) -> TaskEnv {
    let mut cfg = EnvConfig::default();
    cfg.arm.model = arm;
    TaskEnv::new(cfg).unwrap()
}

#[test]
fn the_arm_at_home_with_the_cube_at_rest_reports_no_collision_for_200_steps() {
    for arm in ARMS {
        let mut env = make_env(arm);
        env.reset(0).unwrap();
        for n in 0..200 {
            let step = env.step(&Action::hold_open()).unwrap();
            assert_eq!(step.info.failure, None, "{arm:?} step {n}");
            assert!(!step.terminated, "{arm:?} step {n}");
            assert_eq!(
                step.truncated,
                n == 199,
                "{arm:?} step {n}: truncated only at the time limit"
            );
        }
    }
}

#[test]
fn driving_the_gripper_into_the_table_is_a_collision_that_names_the_pair() {
    for arm in ARMS {
        let mut env = make_env(arm);
        env.reset(0).unwrap();
        // Shift the cube out of the way, then push the TCP 4 cm below the table top.
        let target = common::beside_and_below_grasp(&env);
        let mut found = None;
        for _ in 0..150 {
            let step = env.step(&common::toward(&env, target, -1.0)).unwrap();
            if step.terminated {
                found = step.info.failure.clone();
                assert_eq!(step.reward, env.config().task.distance.collision);
                assert!(!step.truncated);
                break;
            }
        }
        match found {
            Some(Failure::Collision(a, b)) => {
                assert!(a == "table" || b == "table", "{arm:?}: {a} / {b}");
                let other = if a == "table" { b } else { a };
                assert!(
                    other.starts_with("finger") || other == "palm",
                    "{arm:?}: {other}"
                );
            }
            other => panic!("{arm:?}: expected a table collision, got {other:?}"),
        }
    }
}

fn random_actions(seed: u64, n: usize) -> Vec<Action> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Action(std::array::from_fn(|_| rng.random_range(-1.0..1.0))))
        .collect()
}

fn rollout(env: &mut TaskEnv, seed: u64, actions: &[Action]) -> Vec<[f32; 23]> {
    let (obs, _) = env.reset(seed).unwrap();
    let mut trace = vec![obs.to_array()];
    for a in actions {
        let step = env.step(a).unwrap();
        trace.push(step.obs.to_array());
        if step.terminated || step.truncated {
            break;
        }
    }
    trace
}

#[test]
fn the_same_seed_and_actions_give_bit_identical_observations() {
    let mut cfg = EnvConfig::default();
    cfg.randomization.position = true;
    cfg.randomization.yaw = true;
    cfg.randomization.joint_noise = 0.05;
    for arm in ARMS {
        cfg.arm.model = arm;
        let actions = random_actions(3, 60);
        let mut env = TaskEnv::new(cfg.clone()).unwrap();
        let first = rollout(&mut env, 11, &actions);
        let _ = rollout(&mut env, 12, &actions); // another episode in between
        let again = rollout(&mut env, 11, &actions);
        let fresh = rollout(&mut TaskEnv::new(cfg.clone()).unwrap(), 11, &actions);
        assert_eq!(first, again, "{arm:?}: soft reset replay differs");
        assert_eq!(
            first, fresh,
            "{arm:?}: a fresh env differs from a soft reset"
        );
        let other = rollout(&mut env, 12, &actions);
        assert_ne!(
            first[0], other[0],
            "{arm:?}: different seeds should start differently"
        );
    }
}

#[test]
fn ten_thousand_random_action_steps_stay_finite_in_both_arm_models() {
    for arm in ARMS {
        let mut env = make_env(arm);
        let actions = random_actions(5, 10_000);
        let mut seed = 0;
        env.reset(seed).unwrap();
        for a in &actions {
            let step = env.step(a).unwrap();
            assert!(
                step.obs.to_array().iter().all(|v| v.is_finite()),
                "{arm:?}: {:?}",
                step.obs
            );
            assert!(step.reward.is_finite());
            assert_eq!(step.info.physics_fault, None, "{arm:?}");
            if step.terminated || step.truncated {
                seed += 1;
                env.reset(seed).unwrap();
            }
        }
    }
}

#[test]
fn a_non_finite_physics_state_truncates_the_episode_and_the_next_reset_recovers() {
    let mut env = make_env(ArmSimulation::Servo);
    env.reset(0).unwrap();
    {
        let (world, handles) = env.world_mut();
        let cube = world.bodies.get_mut(handles.cube).unwrap();
        let mut pose = *cube.position();
        pose.translation.x = f32::INFINITY;
        cube.set_position(pose, true);
    }
    let step = env.step(&Action::hold_open()).unwrap();
    assert!(step.truncated && !step.terminated);
    assert!(step.info.physics_fault.is_some());
    assert_eq!(
        env.step(&Action::hold_open()).unwrap_err(),
        EnvError::EpisodeOver
    );
    let (obs, _) = env.reset(0).unwrap();
    assert!(obs.to_array().iter().all(|v| v.is_finite()));
    let step = env.step(&Action::hold_open()).unwrap();
    assert_eq!(step.info.physics_fault, None);
}

#[test]
fn a_nan_action_is_an_error_naming_the_component_and_out_of_range_values_are_clipped() {
    let mut env = make_env(ArmSimulation::Servo);
    env.reset(0).unwrap();
    let mut a = Action::hold_open();
    a.0[3] = f64::NAN;
    let err = env.step(&a).unwrap_err();
    assert!(
        matches!(err, EnvError::NonFiniteAction { index: 3, value } if value.is_nan()),
        "{err}"
    );
    assert!(err.to_string().contains("action[3]"), "{err}");
    // 5.0 moves joint 1 exactly as fast as 1.0 does.
    let mut big = make_env(ArmSimulation::Servo);
    let mut one = make_env(ArmSimulation::Servo);
    big.reset(0).unwrap();
    one.reset(0).unwrap();
    let s_big = big
        .step(&Action([5.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]))
        .unwrap();
    let s_one = one
        .step(&Action([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]))
        .unwrap();
    assert_eq!(s_big.obs.joints, s_one.obs.joints);
    assert!(Action::from_slice(&[0.0; 6]).is_err());
}

#[test]
fn stepping_before_reset_is_an_error() {
    let mut env = make_env(ArmSimulation::Servo);
    assert_eq!(
        env.step(&Action::hold_open()).unwrap_err(),
        EnvError::EpisodeOver
    );
}

#[test]
fn a_joint_velocity_action_moves_the_joint_at_the_scaled_speed() {
    let mut env = make_env(ArmSimulation::Servo);
    let (obs, _) = env.reset(0).unwrap();
    let mut last = obs.joints[0];
    for n in 0..6 {
        let step = env
            .step(&Action([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]))
            .unwrap();
        if n >= 1 {
            // After the 0.05 s ramp at 10 rad/s², the joint moves 0.5 rad/s × 1/12 s per step.
            assert!(
                (step.obs.joints[0] - last - 0.5 / 12.0).abs() < 1e-9,
                "{}",
                step.obs.joints[0] - last
            );
            assert!((step.obs.joint_velocities[0] - 0.5).abs() < 1e-9);
        }
        last = step.obs.joints[0];
    }
}
