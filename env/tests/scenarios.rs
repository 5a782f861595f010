//! Randomisation presets, scenario sets, the curriculum.

use fairgrasp_env::config::RandomizationConfig;
use fairgrasp_env::curriculum::{Curriculum, CurriculumConfig};
use fairgrasp_env::randomize::{Scenario, object_pose_in_base, scenario_set, top_down_grasp};
use fairgrasp_env::{EnvConfig, GraspEnv, HOME_JOINTS};
use fairgrasp_kinematics::{ArmKind, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn every_sample_is_graspable(randomization: RandomizationConfig, base_rpy: [f64; 3]) {
    let mut cfg = EnvConfig::default();
    cfg.arm.base_rpy = base_rpy;
    let model = ArmKind::Fr3.model();
    let base = Pose::from_xyz_rpy(cfg.arm.base_xyz, cfg.arm.base_rpy);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let r = &randomization;
    for n in 0..10_000 {
        // Uniform over the sector, no rejection: the whole preset must be graspable.
        let radius = rng
            .random_range(r.radius[0].powi(2)..=r.radius[1].powi(2))
            .sqrt();
        let angle = rng.random_range(r.angle[0]..=r.angle[1]);
        let yaw = rng.random_range(0.0..std::f64::consts::TAU);
        let pose = object_pose_in_base(
            &cfg,
            &base,
            [radius * angle.cos(), radius * angle.sin()],
            yaw,
        );
        assert!(
            top_down_grasp(
                &model,
                &pose,
                cfg.scene.table_height - cfg.arm.base_xyz[2],
                &HOME_JOINTS
            )
            .is_some(),
            "sample {n}: r {radius:.3} angle {angle:.3}"
        );
    }
}

#[test]
fn every_position_of_the_seed_sector_admits_a_top_down_grasp_within_limits() {
    every_sample_is_graspable(RandomizationConfig::seed_sector(), [0.0; 3]);
}

#[test]
fn every_position_of_the_wide_sector_admits_a_top_down_grasp_within_limits() {
    every_sample_is_graspable(RandomizationConfig::wide_sector(), [0.0; 3]);
}

#[test]
fn a_rotated_base_changes_nothing_in_the_base_frame() {
    every_sample_is_graspable(RandomizationConfig::seed_sector(), [0.0, 0.0, 2.0]);
}

#[test]
fn a_scenario_set_is_identical_for_the_same_seed_and_differs_for_another() {
    let cfg = EnvConfig {
        randomization: RandomizationConfig::full(),
        ..EnvConfig::default()
    };
    let model = ArmKind::Fr3.model();
    let base = Pose::from_xyz_rpy(cfg.arm.base_xyz, cfg.arm.base_rpy);
    let a = scenario_set(&cfg, &model, &base, 7, 50).unwrap();
    let b = scenario_set(&cfg, &model, &base, 7, 50).unwrap();
    let c = scenario_set(&cfg, &model, &base, 8, 50).unwrap();
    assert_eq!(a, b);
    assert_ne!(a, c);
    let r = &cfg.randomization;
    for s in &a {
        let radius = s.object_xy[0].hypot(s.object_xy[1]);
        assert!(radius >= r.radius[0] - 1e-12 && radius <= r.radius[1] + 1e-12);
        let friction = r.friction.unwrap();
        assert!(s.friction >= friction[0] && s.friction <= friction[1]);
        assert!(s.mass >= 0.08 - 1e-12 && s.mass <= 0.12 + 1e-12);
        assert!(model.in_limits(&s.start_joints, 0.0));
    }
}

#[test]
fn reset_to_a_scenario_puts_the_cube_where_it_says_resting_on_the_table() {
    let mut cfg = EnvConfig {
        randomization: RandomizationConfig::seed_sector(),
        ..EnvConfig::default()
    };
    cfg.arm.base_rpy = [0.0, 0.0, 0.7]; // a rotated base: positions are in its frame
    let mut env = GraspEnv::new(cfg.clone()).unwrap();
    let scenario = Scenario::sample(&cfg, env.model(), env.base_in_world(), 4).unwrap();
    env.reset_to(&scenario);
    let xyz = env.object_in_base().xyz();
    assert!(
        (xyz[0] - scenario.object_xy[0]).abs() < 2e-3
            && (xyz[1] - scenario.object_xy[1]).abs() < 2e-3,
        "{xyz:?} vs {scenario:?}"
    );
    // Resting: the centre half a cube above the table top (base at the table height), not inside it.
    assert!(
        (xyz[2] - cfg.scene.cube_size / 2.0).abs() < 1.5e-3,
        "{xyz:?}"
    );
}

#[test]
fn the_curriculum_advances_only_past_the_threshold_over_a_full_window() {
    let config = CurriculumConfig {
        threshold: 0.6,
        window: 10,
    };
    let mut c = Curriculum::new(config, RandomizationConfig::full());
    assert_eq!(c.stage(), 0);
    assert!(!c.randomization().position);
    for i in 0..10 {
        assert!(!c.record(i % 2 == 0), "50 % must not advance");
    }
    assert_eq!(c.stage(), 0);
    let mut advanced = false;
    for _ in 0..10 {
        advanced |= c.record(true);
    }
    assert!(advanced);
    assert_eq!(c.stage(), 1);
    assert!(c.randomization().position && !c.randomization().yaw);
    for _ in 0..20 {
        c.record(true);
    }
    assert_eq!(c.stage(), 3);
    assert_eq!(c.randomization(), RandomizationConfig::full());
    for _ in 0..20 {
        assert!(!c.record(true), "no stage after the last");
    }
}

#[test]
fn perception_noise_shifts_only_the_observed_cube_and_is_fixed_per_episode() {
    let config = fairgrasp_env::presets::load("hard").unwrap();
    let mut env = GraspEnv::new(config).unwrap();
    let (obs, info) = env.reset(3).unwrap();
    let scenario = info.scenario.unwrap();
    let actual = env.object_in_base().xyz();
    let observed = obs.object_position();
    for i in 0..3 {
        assert!((observed[i] - actual[i] - scenario.observed_position_error[i]).abs() < 1e-9);
    }
    assert!(
        scenario.observed_position_error[0].abs() + scenario.observed_position_error[1].abs()
            > 1e-4
    );
    let yaw_error = obs.object_yaw - env.object_in_base().rpy()[2];
    let wrapped = (yaw_error - scenario.observed_yaw_error + std::f64::consts::PI)
        .rem_euclid(std::f64::consts::TAU)
        - std::f64::consts::PI;
    assert!(
        wrapped.abs() < 1e-6,
        "{yaw_error} vs {}",
        scenario.observed_yaw_error
    );
    // The same error on the next step: it is per episode, not per step.
    let step = env.step(&fairgrasp_env::Action::hold_open()).unwrap();
    let after = step.obs.object_position();
    let now = env.object_in_base().xyz();
    assert!((after[0] - now[0] - scenario.observed_position_error[0]).abs() < 1e-9);
}
