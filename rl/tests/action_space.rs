//! The pure agent's task-space action (the env's, with the recipe's options) and the
//! training-only `[env]` settings of a run config.

use burn::tensor::Device;
use fairgrasp_env::config::presets;
use fairgrasp_env::config::{ActionSpace, GripperCommand, RewardKind, TcpSaturation};
use fairgrasp_env::episode::run_episode;
use fairgrasp_env::episode::trajectory::Trajectory;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{Action, TaskEnv};
use fairgrasp_policy::recipe::EnvFor;
use fairgrasp_rl::agent::grasp_agent::Mode;
use fairgrasp_rl::run::checkpoint::load_model;
use fairgrasp_rl::run::evaluate::agent_policy;
use fairgrasp_rl::run::shipped::ShippedPolicy;
use fairgrasp_rl::run::train::TrainConfig;

#[test]
fn a_task_space_action_becomes_joint_actions_that_move_the_tcp_that_way() {
    let config = presets::load("fixed").unwrap();
    let agent = fairgrasp_rl::agent::AgentConfig {
        mode: Mode::Pure,
        action_space: ActionSpace::Tcp,
        ..Default::default()
    };
    let map = agent.task_space(&config).unwrap();
    let mut env = TaskEnv::new(config).unwrap();
    env.reset(0).unwrap();
    let start = env.tcp_in_base().xyz();
    // Straight down and to the left; a positive gripper command closes it fully (binary).
    let tcp = Action([0.0, 0.6, -0.6, 0.0, 0.0, 0.0, 0.5]);
    for _ in 0..6 {
        let action = Action(map.to_joint_action(&env.joints(), &tcp.0));
        assert!(
            action.0.iter().all(|v| v.abs() <= 1.0 + 1e-12),
            "{action:?}"
        );
        assert_eq!(action.0[6], 1.0);
        assert_eq!(
            map.to_joint_action(&env.joints(), &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.1])[6],
            -1.0
        );
        env.step(&action).unwrap();
    }
    let end = env.tcp_in_base().xyz();
    let moved = [end[0] - start[0], end[1] - start[1], end[2] - start[2]];
    assert!(moved[1] > 0.03 && moved[2] < -0.03, "{moved:?}");
    assert!(moved[0].abs() < 0.1 * moved[1], "{moved:?}");
}

#[test]
fn the_shipped_pure_policy_acts_the_same_through_an_env_configured_for_its_task_space_action() {
    // Two ways to the same motion: the agent maps its task-space output to joint actions for a
    // joint-mode env (how it trained), or hands it as it is to an env configured with the
    // recipe's task-space action (`tcp`, saturated at action_scale, binary gripper).
    let dir = ShippedPolicy::PureFull.checkpoint_dir().unwrap();
    let (meta, model) = load_model(&dir, &Device::flex()).unwrap();
    assert_eq!(
        (meta.agent.mode, meta.agent.action_space),
        (Mode::Pure, ActionSpace::Tcp)
    );
    let joint_config = presets::load("sector").unwrap();
    let tcp_config = meta.agent.env_for(&joint_config);
    assert_eq!(
        (
            tcp_config.arm.action_space,
            tcp_config.arm.tcp_saturation,
            tcp_config.arm.gripper_command
        ),
        (
            ActionSpace::Tcp,
            TcpSaturation::ActionScale,
            GripperCommand::Binary
        )
    );
    let mut raw_meta = meta.clone();
    raw_meta.agent.action_space = ActionSpace::Joint; // pure + joint: the output, clipped
    let mut through_agent = agent_policy(&meta, &model, &joint_config);
    let mut through_env = agent_policy(&raw_meta, &model, &tcp_config);
    let mut joint_env = TaskEnv::new(joint_config.clone()).unwrap();
    let mut tcp_env = TaskEnv::new(tcp_config).unwrap();
    let mut successes = 0;
    for s in &scenario_set(&joint_config, 11, 12).unwrap() {
        let (mut a, mut b) = (Trajectory::default(), Trajectory::default());
        let ra = run_episode(&mut joint_env, &mut through_agent, s, Some(&mut a)).unwrap();
        let rb = run_episode(&mut tcp_env, &mut through_env, s, Some(&mut b)).unwrap();
        assert_eq!(ra, rb, "scenario {}", s.seed);
        let joints = |t: &Trajectory| t.rows.iter().map(|r| r.joints).collect::<Vec<_>>();
        assert_eq!(joints(&a), joints(&b), "scenario {}", s.seed);
        successes += usize::from(ra.outcome == fairgrasp_env::episode::Outcome::Success);
    }
    assert!(
        successes >= 9,
        "pure_full succeeded on {successes} of 12 only"
    );
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
    let train = c.env_configs(EnvFor::Training).unwrap().remove(0);
    let eval = c.env_configs(EnvFor::Evaluation).unwrap().remove(0);
    assert_eq!(train.task.reward, RewardKind::Staged);
    assert_eq!(train.task.max_steps, 100);
    assert_eq!(train.task.staged.success, 5.0);
    // Everything not overridden is the preset's, and evaluation uses the preset as it is.
    assert_eq!(train.randomization, eval.randomization);
    assert_eq!(eval.task.reward, RewardKind::Distance);
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
