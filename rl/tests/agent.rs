//! The residual agent: starts exactly at the baseline, checkpoints round-trip, bad inputs are
//! refused clearly, and a resumed run continues where it stopped.

use burn::tensor::Device;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{TaskEnv, config::presets};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use fairgrasp_rl::agent::grasp_agent::{ACT_DIM, AgentConfig};
use fairgrasp_rl::ppo::PpoConfig;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::run::checkpoint::{self, CheckpointMeta};
use fairgrasp_rl::run::train::{TrainConfig, agent_policy, train};

fn fresh_meta(agent: AgentConfig) -> (CheckpointMeta, ActorCritic) {
    let model_config = ModelConfig {
        zero_actor_output: true,
        log_std_init: -1.0,
        ..ModelConfig::default()
    };
    let input_dim = agent.input_dim();
    let model = ActorCritic::new(input_dim, ACT_DIM, &model_config, 0, &Device::flex());
    let meta = CheckpointMeta::fresh(model_config, agent, true);
    (meta, model)
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-rl-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn a_fresh_residual_agent_acts_exactly_like_the_baseline() {
    let config = presets::load("sector").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let scenario = scenario_set(&config, 4, 1).unwrap()[0];
    let (meta, model) = fresh_meta(AgentConfig::default());
    let mut agent = agent_policy(&meta, &model, &config);
    let mut baseline = ScriptedGrasp::new(&config, BaselineConfig::default());
    let (mut obs, _) = env.reset_to(&scenario);
    agent.reset(0);
    baseline.reset(0);
    for _ in 0..60 {
        let a = agent.act(&obs);
        let b = baseline.act(&obs);
        assert_eq!(a, b);
        let step = env.step(&a).unwrap();
        if step.terminated || step.truncated {
            break;
        }
        obs = step.obs;
    }
}

#[test]
fn a_checkpoint_round_trip_gives_identical_actions() {
    let dir = temp_dir("roundtrip");
    let agent = AgentConfig::default();
    let model_config = ModelConfig::default(); // random actor output, so the test can fail
    let input_dim = agent.input_dim();
    let device = Device::flex();
    let model = ActorCritic::new(input_dim, ACT_DIM, &model_config, 0, &device);
    let (mut meta, _) = fresh_meta(agent);
    meta.model = model_config;
    meta.obs_norm
        .update(&[vec![0.5; input_dim], vec![-0.2; input_dim]]);
    checkpoint::save(&dir, &meta, &model, None).unwrap();
    let (loaded_meta, loaded) = checkpoint::load_model(&dir, &device).unwrap();
    assert!(
        loaded_meta.model_checksum.is_some(),
        "saved without a checksum"
    );
    let without_checksum = CheckpointMeta {
        model_checksum: None,
        version: meta.version,
        ..loaded_meta.clone()
    };
    assert_eq!(loaded_meta.version, checkpoint::CHECKPOINT_VERSION);
    assert_eq!(without_checksum, meta);
    let config = presets::load("sector").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let (obs, _) = env.reset(1).unwrap();
    let mut a = agent_policy(&meta, &model, &config);
    let mut b = agent_policy(&loaded_meta, &loaded, &config);
    let (x, y) = (a.act(&obs), b.act(&obs));
    assert_eq!(x, y);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_corrupted_checkpoint_gives_an_error_naming_the_file() {
    let dir = temp_dir("corrupt");
    let (meta, model) = fresh_meta(AgentConfig::default());
    checkpoint::save(&dir, &meta, &model, None).unwrap();
    std::fs::write(dir.join("model.bpk"), b"not a burnpack file").unwrap();
    let e = checkpoint::load_model(&dir, &Device::flex())
        .unwrap_err()
        .to_string();
    assert!(e.contains("model.bpk") && e.contains("checksum"), "{e}");
    std::fs::write(dir.join("meta.json"), b"{\"version\": 1").unwrap();
    let e = checkpoint::load_meta(&dir).unwrap_err().to_string();
    assert!(
        e.contains("meta.json") && e.contains("not a valid checkpoint"),
        "{e}"
    );
    let e = checkpoint::load_meta(&temp_dir("missing"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no meta.json"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_bad_training_config_is_refused_with_the_field() {
    let mut c = TrainConfig::default();
    c.ppo.n_steps = 100;
    c.ppo.batch_size = 64;
    let e = c.validate().unwrap_err();
    assert!(e.contains("batch_size 64"), "{e}");
    let c = TrainConfig {
        preset: "nope".into(),
        ..TrainConfig::default()
    };
    assert!(c.validate().unwrap_err().contains("no such preset"));
    let dir = temp_dir("badtoml");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("train.toml");
    std::fs::write(&path, "total_timestepz = 5\n").unwrap();
    let e = TrainConfig::from_toml_file(&path).unwrap_err().to_string();
    assert!(
        e.contains("train.toml") && e.contains("total_timestepz"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn tiny(total: u64) -> TrainConfig {
    TrainConfig {
        preset: "fixed".into(),
        total_timesteps: total,
        n_envs: 2,
        threads: 1,
        eval_every: 0,
        eval_episodes: 2,
        ppo: PpoConfig {
            n_steps: 16,
            batch_size: 16,
            n_epochs: 2,
            ..PpoConfig::default()
        },
        ..TrainConfig::default()
    }
}

#[test]
fn resume_continues_the_timestep_count_and_the_metrics() {
    let dir = temp_dir("resume");
    train(&tiny(64), &dir, false, &mut |_| {}).unwrap();
    let meta = checkpoint::load_meta(&dir.join("checkpoints/latest")).unwrap();
    assert_eq!((meta.timesteps, meta.updates), (64, 2));
    // As if written before the outcome columns existed: the leading 16 columns only.
    let csv = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    let old: String = csv
        .lines()
        .map(|l| l.split(',').take(16).collect::<Vec<_>>().join(",") + "\n")
        .collect();
    std::fs::write(dir.join("metrics.csv"), old).unwrap();
    let mut seen = Vec::new();
    train(&tiny(128), &dir, true, &mut |p| seen.push(p.timesteps)).unwrap();
    assert_eq!(seen, vec![96, 128], "resumed from 64, not from 0");
    let csv = std::fs::read_to_string(dir.join("metrics.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 1 + 4, "header + 4 updates");
    let columns = rows[0].split(',').count();
    assert!(
        rows[0].ends_with("outcome_physics_fault,steps_per_second,kickstart_loss"),
        "{}",
        rows[0]
    );
    assert!(
        rows.iter().all(|r| r.split(',').count() == columns),
        "the old rows were not padded: {csv}"
    );
    assert!(rows[4].starts_with("4,128,"), "{}", rows[4]);
    // Wall time keeps counting across the resume.
    let wall = |row: &str| row.split(',').nth(2).unwrap().parse::<f64>().unwrap();
    assert!(
        wall(rows[3]) >= wall(rows[2]) && wall(rows[4]) >= wall(rows[3]),
        "{csv}"
    );
    assert!(dir.join("config.toml").exists());
    std::fs::remove_dir_all(&dir).ok();
}
