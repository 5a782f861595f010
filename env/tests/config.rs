//! Configuration: defaults, TOML round trip, and refusals that name the field.

use fairgrasp_env::config::RandomizationConfig;
use fairgrasp_env::{ConfigError, EnvConfig, EnvError, TaskEnv};

#[test]
fn defaults_are_the_seeds_numbers() {
    let c = EnvConfig::default();
    assert_eq!(c.physics.dt, 1.0 / 240.0);
    assert_eq!(c.physics.substeps, 20);
    assert_eq!(c.task.max_steps, 200);
    assert_eq!(
        (c.scene.cube_size, c.scene.cube_mass, c.scene.cube_friction),
        (0.05, 0.1, 0.8)
    );
    assert_eq!(c.scene.table_friction, 1.2);
    assert_eq!(c.arm.action_scale, 0.5);
    assert_eq!(
        (
            c.task.distance.success,
            c.task.distance.collision,
            c.task.distance.distance
        ),
        (10.0, -1.0, -0.005)
    );
    c.validate().unwrap();
}

#[test]
fn toml_round_trips_and_missing_fields_take_defaults() {
    let c = EnvConfig {
        randomization: RandomizationConfig::full(),
        ..EnvConfig::default()
    };
    let back = EnvConfig::from_toml_str(&c.to_toml()).unwrap();
    assert_eq!(back, c);
    let partial = EnvConfig::from_toml_str("[task]\nmax_steps = 50\n").unwrap();
    assert_eq!(partial.task.max_steps, 50);
    assert_eq!(partial.physics, EnvConfig::default().physics);
}

fn refused(toml: &str) -> String {
    EnvConfig::from_toml_str(toml).unwrap_err().to_string()
}

#[test]
fn invalid_values_are_refused_naming_the_field() {
    assert!(refused("[physics]\nsubsteps = 0\n").contains("physics.substeps"));
    assert!(refused("[scene]\ncube_mass = -0.1\n").contains("scene.cube_mass"));
    assert!(refused("[scene]\ntable_friction = -1.0\n").contains("scene.table_friction"));
    let m = refused("[randomization]\nfriction = [1.0, 0.3]\n");
    assert!(
        m.contains("randomization.friction") && m.contains("min must not exceed max"),
        "{m}"
    );
    assert!(refused("[randomization]\nradius = [0.3, 0.2]\n").contains("randomization.radius"));
    assert!(
        refused("[arm]\nhome_joints = [0.0, 2.0, 0.0, 0.0, 0.0, 0.0]\n")
            .contains("arm.home_joints")
    );
    assert!(
        refused("[task]\nmax_stepz = 3\n").contains("max_stepz"),
        "unknown fields are refused"
    );
    assert!(refused("[arm]\nmodel = \"hydraulic\"\n").contains("hydraulic"));
}

#[test]
fn the_place_tasks_contact_conditions_and_search_tuning_are_refused_out_of_range() {
    for (toml, field, rule) in [
        ("grip_tilt = [0.1, 0.5]", "task.place.grip_tilt", "0.35"),
        (
            "grip_tilt = [0.2, 0.1]",
            "task.place.grip_tilt",
            "min must not exceed max",
        ),
        (
            "fixture_friction = [0.5, 3.0]",
            "task.place.fixture_friction",
            "[0, 2]",
        ),
        (
            "fixture_friction = [-0.1, 1.0]",
            "task.place.fixture_friction",
            "both ends must be in [0, 2]",
        ),
        (
            "search = { contact_force = 0.0 }",
            "task.place.search.contact_force",
            "[0.1, 30] N",
        ),
        (
            "search = { speed = 1.0 }",
            "task.place.search.speed",
            "[0.001, 0.1] m/s",
        ),
        (
            "search = { floor_band = 0.02 }",
            "task.place.search.floor_band",
            "wall_height",
        ),
        ("search = { pich = 0.002 }", "pich", "unknown field"),
        (
            "search = { descend_speed = 0.2 }",
            "task.place.search.descend_speed",
            "[0.001, 0.05] m/s",
        ),
        ("takt = 0.0", "task.place.takt", "(0, 3600] s"),
        (
            "square = { squeeze = 0.1 }",
            "task.place.square.squeeze",
            "[0.2, 100] N",
        ),
        (
            "square = { search = { pitch = 0.5 } }",
            "task.place.square.search.pitch",
            "[0.0005, 0.02]",
        ),
        (
            "switch = { tilted = { floor_band = 0.05 } }",
            "task.place.switch.tilted.floor_band",
            "wall_height",
        ),
        (
            "switch = { tilt_band = 0.05 }",
            "task.place.switch.tilt_band",
            "[0.0001, 0.01] m",
        ),
    ] {
        let m = refused(&format!("[task]\nkind = \"place\"\n[task.place]\n{toml}\n"));
        assert!(m.contains(field) && m.contains(rule), "{toml}: {m}");
    }
    let ok = "[task]\nkind = \"place\"\n[task.place]\ngrip_tilt = [0.07, 0.17]\n\
              fixture_friction = [0.3, 1.2]\nsearch = { pitch = 0.002 }\n";
    let config = EnvConfig::from_toml_str(ok).unwrap();
    assert_eq!(config.task.place.search.pitch, 0.002);
    assert_eq!(
        config.task.place.search.contact_force, 1.5,
        "the rest default"
    );
}

/// An angle range may be negative, down to −π, and goes up to π (one turn, issue 70: its
/// upper end had no bound): the message states those bounds, not "must not be negative"
/// (issue 60's example).
#[test]
fn an_angle_range_beyond_a_turn_is_refused_stating_its_real_bound() {
    for angle in ["[-3.5, 1.0]", "[-1.0, 3.5]"] {
        let m = refused(&format!("[randomization]\nangle = {angle}\n"));
        assert!(
            m.contains("randomization.angle")
                && m.contains("3.5")
                && m.contains("[-3.141592653589793, 3.141592653589793] rad"),
            "{m}"
        );
        assert!(!m.contains("negative"), "{m}");
    }
    EnvConfig::from_toml_str("[randomization]\nangle = [-3.0, 3.0]\n").unwrap();
}

#[test]
fn a_config_file_error_names_the_file() {
    let dir = std::env::temp_dir().join(format!("fairgrasp-env-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.toml");
    std::fs::write(&path, "[physics]\ndt = 0.0\n").unwrap();
    let err = EnvConfig::from_toml_file(&path).unwrap_err().to_string();
    assert!(
        err.contains("bad.toml") && err.contains("physics.dt"),
        "{err}"
    );
    assert!(
        EnvConfig::from_toml_file(dir.join("missing.toml"))
            .unwrap_err()
            .to_string()
            .contains("missing.toml")
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_env_refuses_an_invalid_config_at_construction() {
    let mut c = EnvConfig::default();
    c.physics.substeps = 0;
    match TaskEnv::new(c) {
        Err(EnvError::Config(ConfigError::Invalid { field, .. })) => {
            assert_eq!(field, "physics.substeps")
        }
        Err(other) => panic!("wrong error: {other}"),
        Ok(_) => panic!("accepted zero substeps"),
    }
}

#[test]
fn the_shipped_presets_equal_the_rust_presets() {
    let expected = [
        ("fixed", RandomizationConfig::default()),
        ("sector", RandomizationConfig::sector()),
        ("wide", RandomizationConfig::wide_sector()),
        ("full", RandomizationConfig::full()),
        ("hard", RandomizationConfig::hard()),
    ];
    for (name, randomization) in expected {
        let config = fairgrasp_env::config::presets::load(name).unwrap();
        assert_eq!(config.randomization, randomization, "{name}");
        assert_eq!(config.physics, EnvConfig::default().physics, "{name}");
        let file = format!(
            "{}/../assets/configs/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        assert_eq!(EnvConfig::from_toml_file(file).unwrap(), config, "{name}");
    }
    let err = fairgrasp_env::config::presets::load("easy")
        .unwrap_err()
        .to_string();
    assert!(err.contains("fixed, sector, wide, full, hard"), "{err}");
}

#[test]
fn the_old_preset_name_loads_the_same_config_and_is_reported_as_renamed() {
    use fairgrasp_env::config::presets::{self, RENAMED_PRESETS, current_name, rename_note};
    assert_eq!(RENAMED_PRESETS, [("seed", "sector")]);
    assert_eq!(current_name("seed"), ("sector", true));
    assert_eq!(current_name("sector"), ("sector", false));
    assert_eq!(current_name("cell.toml"), ("cell.toml", false));
    assert_eq!(
        presets::load("seed").unwrap(),
        presets::load("sector").unwrap()
    );
    assert_eq!(
        rename_note("seed").unwrap(),
        "preset \"seed\" is now called \"sector\"; the old name still works for now"
    );
    assert_eq!(rename_note("sector"), None);
    // Only the current name is listed.
    assert!(presets::PRESETS.iter().all(|(n, _, _)| *n != "seed"));
}

#[test]
fn a_config_naming_the_old_reward_seed_loads_as_the_distance_reward() {
    use fairgrasp_env::config::RewardKind;
    let old = EnvConfig::from_toml_str("[task]\nreward = \"seed\"\n").unwrap();
    assert_eq!(old.task.reward, RewardKind::Distance);
    let new = EnvConfig::from_toml_str("[task]\nreward = \"distance\"\n").unwrap();
    assert_eq!(old, new);
    assert_eq!(EnvConfig::default().task.reward, RewardKind::Distance);
    // Written back with the current name.
    assert!(
        old.to_toml().contains("reward = \"distance\""),
        "{}",
        old.to_toml()
    );
}

#[test]
fn the_distance_rewards_weights_keep_their_task_keys_in_the_toml() {
    let text = "[task]\nsuccess_reward = 5.0\ncollision_reward = -2.0\ndistance_reward = -0.01\n";
    let c = EnvConfig::from_toml_str(text).unwrap();
    let w = c.task.distance;
    assert_eq!((w.success, w.collision, w.distance), (5.0, -2.0, -0.01));
    let written = c.to_toml();
    assert!(written.contains("success_reward = 5.0"), "{written}");
    assert!(!written.contains("seed_reward"), "{written}");
    assert_eq!(EnvConfig::from_toml_str(&written).unwrap(), c);
    let err = EnvConfig::from_toml_str("[task]\nseed_reward = 1.0\n").unwrap_err();
    assert!(err.to_string().contains("seed_reward"), "{err}");
}
