//! The task-space action (`arm.action_space = "tcp"`) and the staged reward, in the env.

mod common;

use fairgrasp_env::config::{ActionSpace, RewardKind};
use fairgrasp_env::{Action, ArmSimulation, EnvConfig, TaskEnv};

fn tcp_env(reward: RewardKind) -> TaskEnv {
    let mut config: EnvConfig = common::config(ArmSimulation::Servo);
    config.arm.action_space = ActionSpace::Tcp;
    config.task.reward = reward;
    TaskEnv::new(config).unwrap()
}

/// A proportional task-space action toward `target` (base_link = table frame, level base).
fn toward(env: &TaskEnv, target: [f64; 3], grip: f64) -> Action {
    let tcp = env.tcp_in_base().xyz();
    let speed = env.config().arm.tcp_speed;
    let mut a = [0.0; 7];
    for k in 0..3 {
        a[k] = ((target[k] - tcp[k]) * 8.0 / speed).clamp(-1.0, 1.0);
    }
    a[6] = grip;
    Action(a)
}

#[test]
fn tcp_actions_move_the_gripper_straight_to_a_point_and_keep_it_pointing_down() {
    let mut env = tcp_env(RewardKind::Distance);
    env.reset(0).unwrap();
    let start = env.tcp_in_base().xyz();
    let target = [start[0] + 0.08, start[1] - 0.10, start[2] - 0.05];
    let mut worst_tilt = 0.0_f64;
    for _ in 0..40 {
        let step = env.step(&toward(&env, target, -1.0)).unwrap();
        assert!(step.info.failure.is_none(), "{:?}", step.info.failure);
        let approach = env.tcp_in_base().iso.rotation * nalgebra::Vector3::z();
        worst_tilt = worst_tilt.max(approach.angle(&-nalgebra::Vector3::z()));
    }
    let end = env.tcp_in_base().xyz();
    let error = (0..3)
        .map(|k| (end[k] - target[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    eprintln!(
        "error {error:.4} m, worst tilt {:.2}°",
        worst_tilt.to_degrees()
    );
    assert!(error < 0.005, "ended {error} m from the target");
    assert!(worst_tilt < 2f64.to_radians(), "tilted {worst_tilt} rad");
}

#[test]
fn a_yaw_action_turns_the_gripper_about_the_vertical() {
    let mut env = tcp_env(RewardKind::Distance);
    env.reset(0).unwrap();
    let yaw = |env: &TaskEnv| {
        let x = env.tcp_in_base().iso.rotation * nalgebra::Vector3::x();
        x.y.atan2(x.x)
    };
    let before = yaw(&env);
    for _ in 0..6 {
        env.step(&Action([0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0]))
            .unwrap();
    }
    let turned = yaw(&env) - before;
    // 6 steps of 1/12 s at up to tcp_yaw_rate (1 rad/s), less the acceleration ramp.
    assert!(turned > 0.3 && turned < 0.5 + 1e-9, "turned {turned} rad");
}

#[test]
fn the_staged_reward_grows_as_the_gripper_nears_the_cube() {
    let mut env = tcp_env(RewardKind::Staged);
    env.reset(0).unwrap();
    let cube = env.object_in_base().xyz();
    let above = [cube[0], cube[1], cube[2] + 0.12];
    let mut rewards = Vec::new();
    for _ in 0..30 {
        let step = env.step(&toward(&env, above, -1.0)).unwrap();
        assert!((0.0..=1.0).contains(&step.reward), "{}", step.reward);
        rewards.push(step.reward);
    }
    // 12 cm above the cube the reach term is (1 − tanh(5 · 0.12)) / 3 = 0.154.
    assert!((rewards[29] - 0.154).abs() < 0.003, "{rewards:?}");
    assert!(rewards[0] < rewards[29] - 0.05, "{rewards:?}");
}

/// The task can be done through the task-space action: straight above the cube, turn to its
/// yaw, descend with the gripper open, close, lift.
#[test]
fn a_scripted_task_space_grasp_lifts_the_cube() {
    let mut config: EnvConfig = fairgrasp_env::config::presets::load("sector").unwrap();
    config.arm.action_space = ActionSpace::Tcp;
    let mut env = TaskEnv::new(config).unwrap();
    let mut successes = 0;
    for seed in 0..10 {
        env.reset(seed).unwrap();
        let yaw_of = |env: &TaskEnv| {
            let x = env.tcp_in_base().iso.rotation * nalgebra::Vector3::x();
            x.y.atan2(x.x)
        };
        let cube = env.object_in_base();
        let c = cube.xyz();
        let cube_yaw = {
            let x = cube.iso.rotation * nalgebra::Vector3::x();
            x.y.atan2(x.x)
        };
        let mut result = None;
        for k in 0..120 {
            // Yaw error modulo the cube's 90° symmetry, in (−45°, 45°].
            let q = std::f64::consts::FRAC_PI_2;
            let e = (cube_yaw - yaw_of(&env) + q / 2.0).rem_euclid(q) - q / 2.0;
            let (target, grip) = match k {
                0..40 => ([c[0], c[1], c[2] + 0.10], -1.0),
                40..70 => ([c[0], c[1], c[2]], -1.0),
                70..80 => ([c[0], c[1], c[2]], 1.0),
                _ => ([c[0], c[1], c[2] + 0.10], 1.0),
            };
            let mut action = toward(&env, target, grip);
            action.0[3] = (e * 4.0).clamp(-1.0, 1.0);
            let step = env.step(&action).unwrap();
            if step.terminated || step.truncated {
                result = Some((step.info.success, step.info.failure));
                break;
            }
        }
        eprintln!("seed {seed}: {result:?}");
        successes += usize::from(matches!(result, Some((true, _))));
    }
    assert!(successes >= 9, "{successes} of 10");
}
