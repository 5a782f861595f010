//! The pure agent's task-space action and the training-only `[env]` settings of a run config.

use fairgrasp_env::config::presets;
use fairgrasp_env::config::{ActionSpace, RewardKind};
use fairgrasp_env::{Action, GraspEnv};
use fairgrasp_rl::agent::action_map::ActionMap;
use fairgrasp_rl::agent::grasp_agent::Mode;
use fairgrasp_rl::run::train::TrainConfig;

#[test]
fn a_task_space_action_becomes_joint_actions_that_move_the_tcp_that_way() {
    let config = presets::load("fixed").unwrap();
    let map = ActionMap::new(&config);
    let mut env = GraspEnv::new(config).unwrap();
    env.reset(0).unwrap();
    let start = env.tcp_in_base().xyz();
    // Straight down and to the left; a positive gripper command closes it fully (binary).
    let tcp = Action([0.0, 0.6, -0.6, 0.0, 0.0, 0.0, 0.5]);
    for _ in 0..6 {
        let action = map.to_joint_action(&env.joints(), &tcp);
        assert!(
            action.0.iter().all(|v| v.abs() <= 1.0 + 1e-12),
            "{action:?}"
        );
        assert_eq!(action.0[6], 1.0);
        assert_eq!(
            map.to_joint_action(&env.joints(), &Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.1]))
                .0[6],
            -1.0
        );
        env.step(&action).unwrap();
    }
    let end = env.tcp_in_base().xyz();
    let moved = [end[0] - start[0], end[1] - start[1], end[2] - start[2]];
    assert!(moved[1] > 0.03 && moved[2] < -0.03, "{moved:?}");
    assert!(moved[0].abs() < 0.1 * moved[1], "{moved:?}");
}

fn config(text: &str) -> TrainConfig {
    toml::from_str(text).unwrap()
}

#[test]
fn env_settings_of_a_training_config_apply_to_training_only() {
    let c = config(
        "preset = \"seed\"\n[agent]\nmode = \"pure\"\naction_space = \"tcp\"\n\
         [env.task]\nreward = \"staged\"\nmax_steps = 100\n[env.task.staged]\nsuccess = 5.0\n",
    );
    c.validate().unwrap();
    let train = c.training_env_config().unwrap();
    let eval = c.env_config().unwrap();
    assert_eq!(train.task.reward, RewardKind::Staged);
    assert_eq!(train.task.max_steps, 100);
    assert_eq!(train.task.staged.success, 5.0);
    // Everything not overridden is the preset's, and evaluation uses the preset as it is.
    assert_eq!(train.randomization, eval.randomization);
    assert_eq!(eval.task.reward, RewardKind::Seed);
    assert_eq!(c.agent.action_space, ActionSpace::Tcp);
    assert_eq!(c.agent.mode, Mode::Pure);
}

#[test]
fn bad_training_env_settings_are_refused_by_name() {
    let bad = config("preset = \"seed\"\n[env.task]\nmax_steps = 0\n");
    let message = bad.validate().unwrap_err();
    assert!(message.contains("task.max_steps"), "{message}");
    let unknown = config("preset = \"seed\"\n[env.task]\nrewrd = \"staged\"\n");
    let message = unknown.validate().unwrap_err();
    assert!(message.contains("rewrd"), "{message}");
    let env_action = config("preset = \"seed\"\n[env.arm]\naction_space = \"tcp\"\n");
    let message = env_action.validate().unwrap_err();
    assert!(message.contains("[agent] action_space"), "{message}");
}
