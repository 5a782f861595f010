//! The scenario families (`miscalibrated`, `miscalibrated_b`, `nudged`): presets that load and
//! validate, bad values refused by name, the camera error applied exactly, the push carried out
//! once, by the drawn amount, onto the table, at rest, never near the gripper; reproducible.

use fairgrasp_env::scenario::camera_offset::CameraOffset;
use fairgrasp_env::scenario::nudge::NudgeEvent;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{Action, EnvConfig, TaskEnv, config::presets};
use fairgrasp_kinematics::Pose;

const FAMILIES: [&str; 3] = ["miscalibrated", "miscalibrated_b", "nudged"];

#[test]
fn the_family_presets_load_validate_and_draw_the_full_presets_scenarios() {
    let full = presets::load("full").unwrap();
    let reference = scenario_set(&full, 0, 20).unwrap();
    for name in FAMILIES {
        let config = presets::load(name).unwrap();
        config.validate().unwrap();
        let file = format!(
            "{}/../assets/configs/{name}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        assert_eq!(EnvConfig::from_toml_file(file).unwrap(), config, "{name}");
        // Only the family's own field differs from `full`.
        let mut plain = config.randomization.clone();
        plain.camera_offset = None;
        plain.nudge = None;
        assert_eq!(plain, full.randomization, "{name}");
        let scenarios = scenario_set(&config, 0, 20).unwrap();
        for (s, r) in scenarios.iter().zip(&reference) {
            assert_eq!(
                (s.object_xy, s.object_yaw, s.start_joints),
                (r.object_xy, r.object_yaw, r.start_joints)
            );
        }
    }
}

fn refused(toml: &str, field: &str) {
    let text = format!("[randomization]\nposition = true\nradius = [0.25, 0.45]\n{toml}\n");
    let err = EnvConfig::from_toml_str(&text).unwrap_err().to_string();
    assert!(err.contains(field), "{toml}: {err}");
}

#[test]
fn bad_family_values_are_refused_naming_the_field() {
    let c = "camera_offset = { origin = [0.35, 0.0], xyz = [0.01, 0.0, 0.0], yaw";
    refused(&format!("{c} = 0.5 }}"), "randomization.camera_offset.yaw");
    refused(
        "camera_offset = { origin = [0.35, 0.0], xyz = [0.2, 0.0, 0.0], yaw = 0.0 }",
        "randomization.camera_offset.xyz",
    );
    refused("camera_offset = { origin = [0.35, 0.0], yaw = 0.0 }", "xyz");
    let n = |d: &str, s: &str, m: &str| {
        format!("nudge = {{ distance = {d}, step = {s}, min_tcp_distance = {m} }}")
    };
    refused(
        &n("[0.0, 0.03]", "[4, 20]", "0.15"),
        "randomization.nudge.distance",
    );
    refused(
        &n("[0.02, 0.3]", "[4, 20]", "0.15"),
        "randomization.nudge.distance",
    );
    refused(
        &n("[0.02, 0.03]", "[20, 4]", "0.15"),
        "randomization.nudge.step",
    );
    refused(
        &n("[0.02, 0.03]", "[4, 500]", "0.15"),
        "randomization.nudge.step",
    );
    refused(
        &n("[0.02, 0.03]", "[4, 20]", "0.05"),
        "randomization.nudge.min_tcp_distance",
    );
}

/// The observed cube in the table frame: centre \[m\] and yaw \[rad\].
fn observed_in_table(env: &TaskEnv, obs: &fairgrasp_env::Observation) -> [f64; 3] {
    env.mount()
        .table_in_base
        .inverse()
        .transform_point(obs.object_position())
}

#[test]
fn the_miscalibration_moves_the_observed_pose_by_exactly_the_configured_transform() {
    for name in ["miscalibrated", "miscalibrated_b"] {
        let config = presets::load(name).unwrap();
        let CameraOffset { origin, xyz, yaw } = config.randomization.camera_offset.unwrap();
        let mut env = TaskEnv::new(config).unwrap();
        for seed in 0..8 {
            let (obs, _) = env.reset(seed).unwrap();
            let truth = env.mount().base_to_table(&env.object_in_base());
            let p = truth.xyz();
            let (dx, dy) = (p[0] - origin[0], p[1] - origin[1]);
            let expected = [
                origin[0] + yaw.cos() * dx - yaw.sin() * dy + xyz[0],
                origin[1] + yaw.sin() * dx + yaw.cos() * dy + xyz[1],
                p[2] + xyz[2],
            ];
            let seen = observed_in_table(&env, &obs);
            for i in 0..3 {
                assert!(
                    (seen[i] - expected[i]).abs() < 1e-9,
                    "{name} {seed}: {seen:?} vs {expected:?}"
                );
            }
            let true_yaw = env.mount().yaw_on_table(&env.object_in_base());
            let turn = (obs.object_yaw - true_yaw - yaw + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(turn.abs() < 1e-9, "{name} {seed}: yaw off by {turn}");
            // The error is the cell's: up to 4 cm over the sector, and never nothing.
            let off = ((seen[0] - p[0]).powi(2) + (seen[1] - p[1]).powi(2)).sqrt();
            assert!((0.002..0.04).contains(&off), "{name} {seed}: {off} m");
        }
    }
}

fn world_xyz(pose: &Pose) -> [f64; 3] {
    pose.xyz()
}

/// Steps `env` with the arm still and the gripper open for `n` steps; returns the cube (base
/// frame) after each.
fn hold_still(env: &mut TaskEnv, n: usize) -> Vec<Pose> {
    (0..n)
        .map(|_| {
            env.step(&Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]))
                .unwrap();
            env.object_in_base()
        })
        .collect()
}

#[test]
fn a_nudge_happens_once_by_the_drawn_amount_and_leaves_the_cube_at_rest_on_the_table() {
    let config = presets::load("nudged").unwrap();
    let table_top = config.scene.table_height;
    let half = config.scene.cube_size / 2.0;
    let nudge = config.randomization.nudge.unwrap();
    let mut env = TaskEnv::new(config).unwrap();
    for seed in 0..12 {
        env.reset(seed).unwrap();
        let drawn = env
            .scenario()
            .unwrap()
            .nudge
            .expect("every scenario is pushed");
        assert!((nudge.step[0]..=nudge.step[1]).contains(&drawn.step));
        let length = drawn.offset_xy[0].hypot(drawn.offset_xy[1]);
        assert!(
            (nudge.distance[0]..=nudge.distance[1]).contains(&length),
            "{length}"
        );
        let before = env.object_in_base();
        let poses = hold_still(&mut env, drawn.step + 12);
        // Untouched until the drawn step, moved in it, still afterwards.
        let moved = |p: &Pose| {
            let (a, b) = (p.xyz(), before.xyz());
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
        };
        for (k, p) in poses.iter().enumerate() {
            let d = moved(p);
            if k < drawn.step {
                assert!(d < 1e-4, "{seed}: moved {d} m at step {k}, before the push");
            } else {
                assert!(
                    (d - length).abs() < 1e-3,
                    "{seed} step {k}: {d} m, drawn {length}"
                );
            }
        }
        let Some(NudgeEvent::Pushed {
            step,
            from,
            to,
            tcp_distance,
        }) = env.nudge_event()
        else {
            panic!("{seed}: {:?}", env.nudge_event());
        };
        assert_eq!(step, drawn.step);
        assert!(tcp_distance >= nudge.min_tcp_distance);
        // Along the drawn direction (table frame), height kept: on the table top.
        let d = env.mount().table_in_world.inverse().transform_vector([
            to[0] - from[0],
            to[1] - from[1],
            to[2] - from[2],
        ]);
        assert!(
            (d[0] - drawn.offset_xy[0]).abs() < 1e-9 && (d[1] - drawn.offset_xy[1]).abs() < 1e-9
        );
        let last = env.base_in_world().compose(poses.last().unwrap());
        assert!(
            (world_xyz(&last)[2] - table_top - half).abs() < 1e-3,
            "{seed}: not on the table"
        );
        // Not turned: the cube's up axis stays up, its yaw unchanged.
        let up = last.transform_vector([0.0, 0.0, 1.0]);
        assert!(up[2] > 0.9999, "{seed}: tilted {up:?}");
        let yaw = |p: &Pose| env.mount().yaw_on_table(p);
        assert!((yaw(poses.last().unwrap()) - yaw(&before)).abs() < 1e-3);
        // At rest: the last steps moved it by less than 0.1 mm.
        let n = poses.len();
        let (a, b) = (poses[n - 1].xyz(), poses[n - 6].xyz());
        assert!(
            (0..3).all(|i| (a[i] - b[i]).abs() < 1e-4),
            "{seed}: still moving"
        );
    }
}

#[test]
fn no_nudge_while_the_gripper_is_near() {
    let config = presets::load("nudged").unwrap();
    let mut env = TaskEnv::new(config).unwrap();
    let (_, info) = env.reset(3).unwrap();
    let mut scenario = info.scenario.unwrap();
    let mut drawn = scenario.nudge.unwrap();
    // The TCP starts ≥ 0.2 m from any cube; demand more than that.
    drawn.min_tcp_distance = 5.0;
    scenario.nudge = Some(drawn);
    env.reset_to(&scenario);
    let before = env.object_in_base().xyz();
    let poses = hold_still(&mut env, drawn.step + 3);
    let after = poses.last().unwrap().xyz();
    assert!(
        (0..3).all(|i| (after[i] - before[i]).abs() < 1e-4),
        "{before:?} → {after:?}"
    );
    let Some(NudgeEvent::Skipped { step, tcp_distance }) = env.nudge_event() else {
        panic!("{:?}", env.nudge_event());
    };
    assert_eq!(step, drawn.step);
    assert!(tcp_distance < 5.0);
}

#[test]
fn the_same_seed_gives_the_same_nudged_episode() {
    let config = presets::load("nudged").unwrap();
    let run = |env: &mut TaskEnv| {
        env.reset(7).unwrap();
        let poses = hold_still(env, 30);
        (
            env.scenario().copied(),
            env.nudge_event(),
            poses.iter().map(|p| p.xyz()).collect::<Vec<_>>(),
        )
    };
    let mut a = TaskEnv::new(config.clone()).unwrap();
    let first = run(&mut a);
    let again = run(&mut a);
    let fresh = run(&mut TaskEnv::new(config).unwrap());
    assert_eq!(first, again);
    assert_eq!(first, fresh);
    assert!(matches!(first.1, Some(NudgeEvent::Pushed { .. })));
}

/// The place cell's mix (`place_cell`, `[task.place.mix]`): over many scenarios each family is
/// drawn at its weight's rate (inside the rate's 99.9 % Wilson interval), every scenario keeps
/// its family's error and only it, and the walls' friction lies in the preset's range.
#[test]
fn the_place_cell_draws_one_familys_error_per_scenario_at_the_mixs_rates() {
    use fairgrasp_env::scenario::error_mix::ErrorFamily;
    let config = presets::load("place_cell").unwrap();
    let mix = config.task.place.mix.expect("place_cell has a mix");
    let n = 1500;
    let scenarios = scenario_set(&config, 3, n).unwrap();
    let mut counts = [0usize; 3];
    for s in &scenarios {
        let f = s.fixture.unwrap();
        let family = f
            .error_family
            .expect("every scenario of a mix has its family");
        counts[ErrorFamily::ALL.iter().position(|&x| x == family).unwrap()] += 1;
        let grasp = s.observed_position_error != [0.0; 3] || s.observed_yaw_error != 0.0;
        let fixture = f.observed_xy_error != [0.0; 2] || f.observed_yaw_error != 0.0;
        let tilt = f.grip_tilt != 0.0;
        assert_eq!(
            (grasp, fixture, tilt),
            (
                family == ErrorFamily::GraspError,
                family == ErrorFamily::FixtureError,
                family == ErrorFamily::Tilted
            ),
            "scenario {}: {family} keeps its own error only",
            s.seed
        );
        if tilt {
            let [lo, hi] = config.task.place.grip_tilt;
            assert!((lo..=hi).contains(&f.grip_tilt.abs()), "{}", f.grip_tilt);
        }
        let friction = f.friction.expect("the walls' friction is drawn");
        assert!((0.3..=1.2).contains(&friction), "{friction}");
    }
    // 99.9 % Wilson interval around each observed rate must hold the weight's probability.
    for ((family, k), p) in ErrorFamily::ALL.iter().zip(counts).zip(mix.probabilities()) {
        let (z, nf, q) = (3.29, n as f64, k as f64 / n as f64);
        let centre = (q + z * z / (2.0 * nf)) / (1.0 + z * z / nf);
        let half = z * (q * (1.0 - q) / nf + z * z / (4.0 * nf * nf)).sqrt() / (1.0 + z * z / nf);
        assert!(
            (centre - half..=centre + half).contains(&p),
            "{family}: {k} of {n}, expected about {p:.3}"
        );
    }
    // A lopsided mix is drawn lopsided: the weights are read, not assumed even.
    let mut lopsided = config.clone();
    lopsided.task.place.mix = Some(fairgrasp_env::scenario::error_mix::ErrorMix {
        fixture_error: 0.0,
        grasp_error: 1.0,
        tilted: 3.0,
    });
    let drawn = scenario_set(&lopsided, 3, 400).unwrap();
    let tilted = drawn
        .iter()
        .filter(|s| s.fixture.unwrap().error_family == Some(ErrorFamily::Tilted))
        .count();
    let fixture = drawn
        .iter()
        .filter(|s| s.fixture.unwrap().error_family == Some(ErrorFamily::FixtureError))
        .count();
    assert_eq!(fixture, 0);
    assert!((260..=340).contains(&tilted), "{tilted} of 400 at 3/4");
}

/// A mix that cannot mean what it says is refused naming the field: a negative or all-zero
/// weight, or a family weighted in whose error the preset never draws.
#[test]
fn a_bad_mix_is_refused_naming_the_field() {
    let base = include_str!("../../assets/configs/place_cell.toml");
    for (patch, field) in [
        ("fixture_error = -1.0", "task.place.mix.fixture_error"),
        (
            "fixture_error = 0.0\ngrasp_error = 0.0\ntilted = 0.0",
            "task.place.mix",
        ),
    ] {
        let text = base.replace(
            "[task.place.mix]\nfixture_error = 1.0\ngrasp_error = 1.0\ntilted = 1.0",
            &format!("[task.place.mix]\n{patch}"),
        );
        let e = EnvConfig::from_toml_str(&text).unwrap_err().to_string();
        assert!(e.contains(field), "{patch}: {e}");
    }
    let no_tilt = base.replace(
        "grip_tilt = [0.06981317007977318, 0.17453292519943295]",
        "grip_tilt = [0.0, 0.0]",
    );
    let e = EnvConfig::from_toml_str(&no_tilt).unwrap_err().to_string();
    assert!(
        e.contains("task.place.mix.tilted") && e.contains("grip_tilt"),
        "{e}"
    );
}
