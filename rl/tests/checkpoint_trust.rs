//! Checkpoints are trusted only when they check out, and a resume never applies a changed
//! config halfway: a flipped byte in the weights, a `meta.json` whose mode or sizes were edited,
//! a resume with a different config (refused, listing the differences, unless accepted; never
//! for the network's shape), and the curriculum stage carried over.

use std::path::{Path, PathBuf};

use burn::tensor::Device;
use fairgrasp_rl::ppo::PpoConfig;
use fairgrasp_rl::ppo::model::ModelConfig;
use fairgrasp_rl::run::checkpoint;
use fairgrasp_rl::run::resume::ResumeOptions;
use fairgrasp_rl::run::train::{TrainConfig, train, train_with};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fairgrasp-trust-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn tiny() -> TrainConfig {
    TrainConfig {
        preset: "fixed".into(),
        total_timesteps: 64,
        n_envs: 2,
        threads: 1,
        eval_every: 0,
        ppo: PpoConfig {
            n_steps: 16,
            batch_size: 16,
            n_epochs: 1,
            ..PpoConfig::default()
        },
        ..TrainConfig::default()
    }
}

fn trained(name: &str) -> PathBuf {
    let dir = temp_dir(name);
    train(&tiny(), &dir, false, &mut |_| {}).unwrap();
    dir
}

fn load_error(dir: &Path) -> String {
    match checkpoint::load_model(dir, &Device::flex()) {
        Ok(_) => panic!("{} loaded", dir.display()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn one_flipped_byte_in_the_weights_is_refused_by_its_checksum() {
    let dir = trained("flip");
    let latest = dir.join("checkpoints/latest");
    assert!(checkpoint::load_model(&latest, &Device::flex()).is_ok());
    let path = latest.join("model.bpk");
    let mut bytes = std::fs::read(&path).unwrap();
    let k = bytes.len() * 2 / 3;
    bytes[k] ^= 0x10;
    std::fs::write(&path, bytes).unwrap();
    let message = load_error(&latest);
    assert!(
        message.contains("model.bpk") && message.contains("checksum"),
        "{message}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// An edit of a checkpoint's `meta.json`.
type MetaEdit = dyn Fn(&mut serde_json::Value);

#[test]
fn a_meta_json_edited_to_another_mode_or_size_is_refused_not_a_panic() {
    let dir = trained("edit");
    let latest = dir.join("checkpoints/latest");
    let meta_path = latest.join("meta.json");
    let original = std::fs::read_to_string(&meta_path).unwrap();
    let edits: [(&str, &MetaEdit); 3] = [
        ("mode pure, input 30", &|m| {
            m["agent"]["mode"] = "pure".into();
            m["input_dim"] = 30.into();
        }),
        ("hidden", &|m| {
            m["model"]["hidden"] = serde_json::json!([64, 32])
        }),
        ("no checksum, hidden", &|m| {
            m.as_object_mut().unwrap().remove("model_checksum");
            m["model"]["hidden"] = serde_json::json!([64, 32]);
        }),
    ];
    for (what, edit) in edits {
        let mut meta: serde_json::Value = serde_json::from_str(&original).unwrap();
        edit(&mut meta);
        std::fs::write(&meta_path, serde_json::to_vec(&meta).unwrap()).unwrap();
        let message = load_error(&latest);
        assert!(message.contains("checkpoint"), "{what}: {message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_resume_with_a_changed_config_is_refused_listing_the_differences_unless_accepted() {
    let dir = trained("config");
    let mut changed = tiny();
    changed.total_timesteps = 128;
    changed.n_envs = 4;
    changed.ppo.learning_rate = 1e-4;
    let refused = train(&changed, &dir, true, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(
        refused.contains("n_envs: 2 → 4")
            && refused.contains("ppo.learning_rate")
            && refused.contains("--accept-config-changes")
            && !refused.contains("total_timesteps"),
        "{refused}"
    );
    let accept = ResumeOptions {
        resume: true,
        accept_config_changes: true,
        ..ResumeOptions::default()
    };
    train_with(&changed, &dir, accept, &mut |_| {}).unwrap();
    let saved = TrainConfig::from_toml_file(&dir.join("config.toml")).unwrap();
    assert_eq!(saved.n_envs, 4, "config.toml must hold what was used");
    let log = std::fs::read_to_string(dir.join("config_changes.log")).unwrap();
    assert!(log.contains("n_envs: 2 → 4"), "{log}");
    // Only the run length changed: no flag needed.
    let mut longer = changed.clone();
    longer.total_timesteps = 256;
    train(&longer, &dir, true, &mut |_| {}).unwrap();
    let saved = TrainConfig::from_toml_file(&dir.join("config.toml")).unwrap();
    assert_eq!(
        saved.total_timesteps, 256,
        "config.toml must hold the run length used"
    );
    // The network's shape can never change on resume, even when accepted.
    let mut wider = longer.clone();
    wider.total_timesteps = 512;
    wider.model = ModelConfig {
        hidden: vec![32],
        ..wider.model
    };
    let shape = train_with(&wider, &dir, accept, &mut |_| {})
        .unwrap_err()
        .to_string();
    assert!(shape.contains("model.hidden"), "{shape}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_curriculum_stage_is_carried_over_a_resume() {
    let dir = temp_dir("stage");
    let mut config = tiny();
    config.curriculum = Some(fairgrasp_env::scenario::curriculum::CurriculumConfig::default());
    train(&config, &dir, false, &mut |_| {}).unwrap();
    // An untrained agent never passes a stage here, so record a run that had reached stage 2.
    let path = dir.join("checkpoints/latest/meta.json");
    let mut meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(meta["curriculum_stage"], 0);
    meta["curriculum_stage"] = 2.into();
    // As format version 1, which had no folder checksum to refuse the edit.
    meta["version"] = 1.into();
    std::fs::write(&path, serde_json::to_vec(&meta).unwrap()).unwrap();
    std::fs::remove_file(path.with_file_name("checksum")).unwrap();
    let mut longer = config.clone();
    longer.total_timesteps = 128;
    let mut stages = Vec::new();
    train(&longer, &dir, true, &mut |p| stages.push(p.stage)).unwrap();
    assert_eq!(stages, [2, 2], "the resumed updates' stages");
    std::fs::remove_dir_all(&dir).ok();
}
