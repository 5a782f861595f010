//! The residual with authority (`mode = "residual"`, `action_space = "tcp"`): untrained it is the
//! open-loop script exactly; its input carries the script's features; it trains and reloads.

use burn::tensor::Device;
use fairgrasp_env::config::ActionSpace;
use fairgrasp_env::episode::{Policy, run_episode};
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{TaskEnv, config::presets};
use fairgrasp_planner::lift::residual::FEATURE_DIM;
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig, Mode, OBS_DIM};
use fairgrasp_rl::agent::task_vec_env::TaskVecEnv;
use fairgrasp_rl::ppo::PpoConfig;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::ppo::vec_api::VecEnvironment;
use fairgrasp_rl::run::checkpoint::{self, CheckpointMeta};
use fairgrasp_rl::run::train::{TrainConfig, agent_policy, train};

fn task_residual() -> AgentConfig {
    AgentConfig {
        mode: Mode::Residual,
        action_space: ActionSpace::Tcp,
        ..AgentConfig::default()
    }
}

fn fresh(agent: AgentConfig, zero: bool) -> (CheckpointMeta, ActorCritic) {
    let model_config = ModelConfig {
        zero_actor_output: zero,
        ..ModelConfig::default()
    };
    let input_dim = agent.input_dim();
    let model = ActorCritic::new(input_dim, ACT_DIM, &model_config, 0, &Device::flex());
    let meta = CheckpointMeta::fresh(model_config, agent, true);
    (meta, model)
}

#[test]
fn an_untrained_task_residual_is_the_open_loop_script_and_a_random_one_is_not() {
    let config = presets::load("miscalibrated").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(&config, 9, 3).unwrap();
    let (meta, model) = fresh(task_residual(), true);
    assert_eq!(meta.input_dim, OBS_DIM + FEATURE_DIM);
    let mut agent = agent_policy(&meta, &model, &config);
    let mut script = ScriptedGrasp::new(&config, BaselineConfig::default());
    let (random_meta, random_model) = fresh(task_residual(), false);
    let mut random = agent_policy(&random_meta, &random_model, &config);
    let mut differs = 0;
    for s in &scenarios {
        let a = run_episode(&mut env, &mut agent, s, None).unwrap();
        let b = run_episode(&mut env, &mut script, s, None).unwrap();
        assert_eq!(a, b, "seed {}", s.seed);
        let c = run_episode(&mut env, &mut random, s, None).unwrap();
        differs += usize::from(c != b);
    }
    assert!(differs > 0, "a random residual changed nothing");
}

#[test]
fn the_vectorised_input_carries_the_phase_and_the_correction() {
    let config = presets::load("fixed").unwrap();
    let agent = task_residual();
    let mut env = TaskVecEnv::new(&config, agent.clone(), 2, 1, 5).unwrap();
    assert_eq!(env.obs_dim(), OBS_DIM + FEATURE_DIM);
    env.reset().unwrap();
    // +y at full rate: the correction feature grows while the script approaches.
    let mut action = vec![0.0f32; 2 * ACT_DIM];
    action[1] = 1.0;
    action[ACT_DIM + 1] = 1.0;
    let mut last = 0.0;
    for k in 0..5 {
        let batch = env.step(&action).unwrap();
        let row = &batch.obs[..OBS_DIM + FEATURE_DIM];
        let features = &row[OBS_DIM..];
        assert_eq!(features[0], 1.0, "step {k}: in the approach {features:?}");
        assert!(features[10] > last, "step {k}: {features:?}");
        last = features[10];
    }
}

#[test]
fn a_task_residual_trains_and_its_checkpoint_reloads() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-rl-taskres-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let config = TrainConfig {
        preset: "miscalibrated".into(),
        total_timesteps: 64,
        n_envs: 2,
        threads: 1,
        eval_every: 0,
        eval_episodes: 2,
        agent: task_residual(),
        ppo: PpoConfig {
            n_steps: 16,
            batch_size: 16,
            n_epochs: 2,
            ..PpoConfig::default()
        },
        ..TrainConfig::default()
    };
    config.validate().unwrap();
    train(&config, &dir, false, &mut |_| {}).unwrap();
    let meta = checkpoint::load_meta(&dir.join("checkpoints/latest")).unwrap();
    assert_eq!(meta.agent.action_space, ActionSpace::Tcp);
    assert_eq!(meta.input_dim, OBS_DIM + FEATURE_DIM);
    assert_eq!(meta.timesteps, 64);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn input_names_match_the_input_and_a_mask_prefix_must_name_some() {
    let lift = presets::load("sector").unwrap();
    let place = presets::load("place").unwrap();
    for agent in [
        task_residual(),
        AgentConfig::default(),
        AgentConfig {
            mode: Mode::Pure,
            ..AgentConfig::default()
        },
    ] {
        for env in [&lift, &place] {
            let names = agent.input_names(env);
            assert_eq!(names.len(), agent.input_dim(), "{agent:?}");
        }
    }
    let agent = task_residual();
    let wrist = agent.input_indices(&lift, "wrist").unwrap();
    assert_eq!(
        wrist,
        (OBS_DIM + 14..OBS_DIM + FEATURE_DIM).collect::<Vec<_>>()
    );
    // On the place task the same prefix names the wrist force.
    let force = agent.input_indices(&place, "wrist").unwrap();
    assert_eq!(force, (OBS_DIM + 6..OBS_DIM + 9).collect::<Vec<_>>());
    let e = agent.input_indices(&lift, "wirst").unwrap_err();
    assert!(e.contains("wirst") && e.contains("wrist_valid"), "{e}");
    assert!(
        AgentConfig::default()
            .input_indices(&lift, "wrist")
            .is_err()
    );
}

#[test]
fn masking_the_wrist_view_changes_nothing_before_the_wrist_camera_sees_the_cube() {
    // A random (non-zero) actor, so the features matter; the wrist camera preset.
    let config = presets::load("wrist_camera").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let s = &scenario_set(&config, 3, 1).unwrap()[0];
    let (meta, model) = fresh(task_residual(), false);
    let wrist = meta.agent.input_indices(&config, "wrist").unwrap();
    let mut plain = agent_policy(&meta, &model, &config);
    let mut masked = agent_policy(&meta, &model, &config).with_masked_inputs(wrist);
    let (mut obs, _) = env.reset_to(s);
    plain.reset(s.seed);
    masked.reset(s.seed);
    // Until the first wrist view both agents see the same input; from then on the masked one
    // acts on a different input (and its correction drifts from what the env does).
    let (mut same_unseen, mut differ_seen, mut viewed) = (true, false, false);
    for _ in 0..120 {
        let a = plain.act(&obs);
        let b = masked.act(&obs);
        viewed |= obs.wrist_camera.is_some();
        if viewed {
            differ_seen |= a != b;
        } else {
            same_unseen &= a == b;
        }
        let step = env.step(&a).unwrap();
        if step.terminated || step.truncated {
            break;
        }
        obs = step.obs;
    }
    assert!(
        same_unseen,
        "masking changed an action without a wrist view"
    );
    assert!(differ_seen, "masking never mattered");
}
