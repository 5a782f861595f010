//! The residual with authority (`mode = "residual"`, `action_space = "tcp"`): untrained it is the
//! open-loop script exactly; its input carries the script's features; it trains and reloads.

use burn::tensor::Device;
use fairgrasp_env::config::ActionSpace;
use fairgrasp_env::policy::run_episode;
use fairgrasp_env::randomize::scenario_set;
use fairgrasp_env::{GraspEnv, presets};
use fairgrasp_planner::residual::FEATURE_DIM;
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_rl::agent::{ACT_DIM, AgentConfig, Mode, OBS_DIM};
use fairgrasp_rl::checkpoint::{self, CheckpointMeta};
use fairgrasp_rl::grasp_env::GraspVecEnv;
use fairgrasp_rl::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::normalizer::RunningNorm;
use fairgrasp_rl::ppo::PpoConfig;
use fairgrasp_rl::train::{TrainConfig, agent_policy, train};
use fairgrasp_rl::vec_api::VecEnvironment;

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
    let model = ActorCritic::new(input_dim, ACT_DIM, &model_config, &Device::flex());
    let meta = CheckpointMeta {
        version: 1,
        input_dim,
        act_dim: ACT_DIM,
        model: model_config,
        agent,
        obs_norm: RunningNorm::new(input_dim, true),
        timesteps: 0,
        updates: 0,
        wall_time_s: 0.0,
        eval_success_rate: None,
    };
    (meta, model)
}

#[test]
fn an_untrained_task_residual_is_the_open_loop_script_and_a_random_one_is_not() {
    let config = presets::load("miscalibrated").unwrap();
    let mut env = GraspEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(&config, env.model(), env.base_in_world(), 9, 3).unwrap();
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
    let mut env = GraspVecEnv::new(&config, agent.clone(), 2, 1, 5).unwrap();
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
