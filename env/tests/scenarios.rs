//! Randomisation presets, scenario sets, the curriculum.

use fairgrasp_env::config::RandomizationConfig;
use fairgrasp_env::scenario::curriculum::{Curriculum, CurriculumConfig};
use fairgrasp_env::scenario::{Scenario, object_pose_in_base, scenario_set, top_down_grasp};
use fairgrasp_env::{EnvConfig, HOME_JOINTS, Mount, TaskEnv};
use fairgrasp_kinematics::ArmKind;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The fraction of 10 000 uniform samples of the sector (no rejection) that admit a top-down
/// grasp from the home joints, with the base at `base_rpy`.
fn graspable_fraction(randomization: RandomizationConfig, base_rpy: [f64; 3]) -> f64 {
    let mut cfg = EnvConfig::default();
    cfg.arm.base_rpy = base_rpy;
    let model = ArmKind::Fr3.model();
    let mount = Mount::from_config(&cfg);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let r = &randomization;
    let n = 10_000;
    let mut graspable = 0;
    for _ in 0..n {
        let radius = rng
            .random_range(r.radius[0].powi(2)..=r.radius[1].powi(2))
            .sqrt();
        let angle = rng.random_range(r.angle[0]..=r.angle[1]);
        let yaw = rng.random_range(0.0..std::f64::consts::TAU);
        let pose = object_pose_in_base(
            &cfg,
            &mount.base_in_world,
            [radius * angle.cos(), radius * angle.sin()],
            yaw,
        );
        if top_down_grasp(&model, &mount, &pose, &HOME_JOINTS).is_some() {
            graspable += 1;
        }
    }
    graspable as f64 / n as f64
}

#[test]
fn every_position_of_the_sector_admits_a_top_down_grasp_within_limits() {
    assert_eq!(
        graspable_fraction(RandomizationConfig::sector(), [0.0; 3]),
        1.0
    );
}

#[test]
fn every_position_of_the_wide_sector_admits_a_top_down_grasp_within_limits() {
    assert_eq!(
        graspable_fraction(RandomizationConfig::wide_sector(), [0.0; 3]),
        1.0
    );
}

/// A base tilted 10° (a wedge mount) and yawed 90°: the table frame is not `base_link`.
const TILTED_YAWED: [f64; 3] = [0.0, 0.1745, std::f64::consts::FRAC_PI_2];

#[test]
fn most_of_the_sector_stays_graspable_from_a_tilted_yawed_base() {
    let f = graspable_fraction(RandomizationConfig::sector(), TILTED_YAWED);
    eprintln!("graspable from the tilted base: {f}");
    assert!(f >= 0.95, "{f}");
}

#[test]
fn scenarios_from_a_tilted_base_rest_flat_on_the_table_and_grasp_along_gravity() {
    for rpy in [TILTED_YAWED, [-0.2, 0.15, -2.0], [0.25, 0.0, 0.0]] {
        let mut cfg = EnvConfig {
            randomization: RandomizationConfig::sector(),
            ..EnvConfig::default()
        };
        cfg.arm.base_rpy = rpy;
        cfg.arm.base_xyz = [0.1, -0.2, cfg.scene.table_height + 0.05]; // on a 5 cm pedestal
        let model = ArmKind::Fr3.model();
        let mount = Mount::from_config(&cfg);
        let base = mount.base_in_world;
        for seed in 0..40 {
            let s = Scenario::sample(&cfg, seed).unwrap();
            let object = object_pose_in_base(&cfg, &base, s.object_xy, s.object_yaw);
            let in_world = base.compose(&object);
            // Resting on the table: centre half a cube above the top, faces level.
            let z = in_world.xyz()[2];
            let half = cfg.scene.cube_size / 2.0;
            assert!(
                (z - cfg.scene.table_height - half).abs() < 1e-9,
                "{rpy:?}: z {z}"
            );
            let up = in_world.transform_vector([0.0, 0.0, 1.0]);
            assert!(up[2] > 1.0 - 1e-9, "{rpy:?}: cube z axis {up:?}");
            // Its horizontal distance from the base is the sampled radius.
            let d = [0, 1].map(|i| in_world.xyz()[i] - base.xyz()[i]);
            let r = s.object_xy[0].hypot(s.object_xy[1]);
            assert!((d[0].hypot(d[1]) - r).abs() < 1e-9);
            // The grasp: tool z along world gravity, TCP at the cube centre, nothing but the
            // base within 2 mm of the table top (in the world).
            let (grasp, above) = top_down_grasp(&model, &mount, &object, &s.start_joints).unwrap();
            let tcp = base.compose(&model.fk_tcp(&grasp));
            let tool_z = tcp.transform_vector([0.0, 0.0, 1.0]);
            assert!(tool_z[2] < -1.0 + 1e-6, "{rpy:?}: tool z {tool_z:?}");
            let (dp, _) = tcp.distance_to(&in_world);
            assert!(dp < 1e-6, "{rpy:?}: TCP {dp} m from the cube centre");
            let pre = base.compose(&model.fk_tcp(&above));
            let rise = [0, 1, 2].map(|i| pre.xyz()[i] - tcp.xyz()[i]);
            assert!(rise[0].hypot(rise[1]) < 1e-6 && (rise[2] - 0.10).abs() < 1e-6);
            for q in [grasp, above] {
                let world_frame = mount.table_in_base;
                assert!(model.lowest_point_in(&q, &world_frame) > 0.002);
            }
        }
    }
}

#[test]
fn a_base_tilted_past_15_degrees_is_refused_naming_the_field() {
    let mut cfg = EnvConfig::default();
    cfg.arm.base_rpy = [0.2, 0.2, 0.0]; // 16.2°
    let err = TaskEnv::new(cfg.clone())
        .err()
        .expect("refused")
        .to_string();
    assert!(err.contains("arm.base_rpy") && err.contains("15°"), "{err}");
    cfg.arm.base_rpy = [0.18, 0.18, 1.0]; // 14.6°
    assert!(TaskEnv::new(cfg).is_ok());
}

#[test]
fn a_mount_with_no_graspable_workspace_is_refused_with_a_message_that_says_so() {
    let mut cfg = EnvConfig {
        randomization: RandomizationConfig::sector(),
        ..EnvConfig::default()
    };
    cfg.arm.base_xyz[2] = cfg.scene.table_height + 1.2; // 1.2 m above the table top
    let mut env = TaskEnv::new(cfg).unwrap();
    let err = env.reset(0).expect_err("no workspace").to_string();
    assert!(
        err.contains("no graspable object position") && err.contains("1.200 m above the table"),
        "{err}"
    );
}

#[test]
fn a_scenario_set_is_identical_for_the_same_seed_and_differs_for_another() {
    let cfg = EnvConfig {
        randomization: RandomizationConfig::full(),
        ..EnvConfig::default()
    };
    let model = ArmKind::Fr3.model();
    let a = scenario_set(&cfg, 7, 50).unwrap();
    let b = scenario_set(&cfg, 7, 50).unwrap();
    let c = scenario_set(&cfg, 8, 50).unwrap();
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
        randomization: RandomizationConfig::sector(),
        ..EnvConfig::default()
    };
    cfg.arm.base_rpy = [0.0, 0.0, 0.7]; // a yawed, level base: positions are in its frame
    let mut env = TaskEnv::new(cfg.clone()).unwrap();
    let scenario = Scenario::sample(&cfg, 4).unwrap();
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
        ..CurriculumConfig::default()
    };
    let mut c = Curriculum::new(config, RandomizationConfig::full(), [0.4, 0.0]);
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
fn narrowed_position_stages_widen_from_the_fixed_cube_to_the_whole_sector() {
    let config = CurriculumConfig {
        threshold: 0.5,
        window: 2,
        position_steps: vec![0.25, 0.5],
        ..CurriculumConfig::default()
    };
    assert!(config.validate().is_ok());
    let full = RandomizationConfig::full();
    let fixed = [0.35, 0.0];
    let mut c = Curriculum::new(config, full.clone(), fixed);
    assert_eq!(c.stage_count(), 6);
    let names: Vec<String> = (0..6).map(|i| c.stage_name(i)).collect();
    assert_eq!(
        names,
        [
            "fixed",
            "position 25 %",
            "position 50 %",
            "position",
            "position+yaw",
            "position+yaw+friction/mass"
        ]
    );
    let (r0, a0) = (fixed[0].hypot(fixed[1]), fixed[1].atan2(fixed[0]));
    let mut widths = Vec::new();
    for stage in 1..=3 {
        c.record(true);
        c.record(true);
        assert_eq!(c.stage(), stage);
        let r = c.randomization();
        assert!(r.position && !r.yaw, "stage {stage}: {r:?}");
        assert!(
            r.radius[0] <= r0 + 1e-12 && r0 <= r.radius[1] + 1e-12,
            "{r:?}"
        );
        assert!(
            r.angle[0] <= a0 + 1e-12 && a0 <= r.angle[1] + 1e-12,
            "{r:?}"
        );
        widths.push((r.radius[1] - r.radius[0], r.angle[1] - r.angle[0]));
    }
    let whole = (
        full.radius[1] - full.radius[0],
        full.angle[1] - full.angle[0],
    );
    assert!((widths[0].0 - 0.25 * whole.0).abs() < 1e-12, "{widths:?}");
    assert!((widths[1].1 - 0.5 * whole.1).abs() < 1e-12, "{widths:?}");
    assert_eq!(widths[2], whole);
    let bad = CurriculumConfig {
        position_steps: vec![0.5, 0.25],
        ..CurriculumConfig::default()
    };
    assert!(
        bad.validate()
            .unwrap_err()
            .contains("curriculum.position_steps")
    );
}

#[test]
fn with_both_sides_a_one_sided_policy_stays_in_its_stage() {
    let config = CurriculumConfig {
        threshold: 0.6,
        window: 10,
        both_sides: true,
        ..CurriculumConfig::default()
    };
    // The fixed cube lies on the +x axis: y > 0 is the left side, y < 0 the right.
    let mut c = Curriculum::new(config, RandomizationConfig::full(), [0.4, 0.0]);
    for _ in 0..10 {
        c.record(true);
    }
    assert_eq!(c.stage(), 1, "the fixed stage has no sides");
    let (left, right) = (Some([0.3, 0.2]), Some([0.3, -0.2]));
    for _ in 0..50 {
        c.record_at(true, left);
        assert!(!c.record_at(false, right), "one side only must not advance");
    }
    assert_eq!(c.stage(), 1);
    assert_eq!(c.side_success_rates(), [1.0, 0.0]);
    let mut advanced = false;
    for i in 0..6 {
        advanced |= c.record_at(true, right);
        // The right window holds 10 − (i + 1) failures and i + 1 successes: 0.6 at i = 5.
        assert_eq!(advanced, i == 5, "after {} right successes", i + 1);
    }
    assert_eq!(c.stage(), 2);
    // A cube behind the base on the left (bearing 170°) is still the left side.
    c.record_at(true, Some([-0.3, 0.05]));
    assert_eq!(c.side_success_rates(), [1.0, 0.0]);
}

#[test]
fn perception_noise_shifts_only_the_observed_cube_and_is_fixed_per_episode() {
    let config = fairgrasp_env::config::presets::load("hard").unwrap();
    let mut env = TaskEnv::new(config).unwrap();
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
