//! "script + calibration": the simulated camera calibration finds the miscalibrated cells'
//! error (the fitted transform maps true cube centres onto what the camera reports within the
//! touch error), finds none where there is none, and the open-loop script on corrected
//! observations grasps where the uncorrected one fails.

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, Policy, run_episode};
use fairgrasp_env::scenario::perception::observe_object;
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{EnvConfig, Mount, TaskEnv};
use fairgrasp_kinematics::Pose;
use fairgrasp_planner::lift::calibrated::TOUCH_ERROR;
use fairgrasp_planner::{BaselineConfig, CalibratedScript, CameraCalibration, ScriptedGrasp};

/// The largest distance \[m\] between the calibration's prediction of what the camera reports and
/// what it does report, and the largest yaw difference \[rad\], over 100 scenarios of `config`.
fn prediction_error(config: &EnvConfig, calibration: &CameraCalibration) -> (f64, f64) {
    let mount = Mount::from_config(config);
    let (mut dp, mut dyaw) = (0.0f64, 0.0f64);
    for s in scenario_set(config, 123, 100).unwrap() {
        let truth = mount.resting_object_in_base(s.object_xy, s.object_yaw, config.scene.cube_size);
        let seen = observe_object(&mount, &truth, Some(&s));
        let predicted = calibration
            .fit
            .as_ref()
            .unwrap()
            .base_in_world
            .transform_point(truth.xyz());
        let d = (0..3)
            .map(|i| (predicted[i] - seen.position[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        dp = dp.max(d);
        let predicted_pose = calibration
            .fit
            .as_ref()
            .unwrap()
            .base_in_world
            .compose(&truth);
        let e = (mount.yaw_on_table(&predicted_pose) - seen.yaw).rem_euclid(std::f64::consts::TAU);
        dyaw = dyaw.max(e.min(std::f64::consts::TAU - e));
    }
    (dp, dyaw)
}

#[test]
fn the_calibration_finds_each_cells_camera_error_and_none_where_there_is_none() {
    for name in ["miscalibrated", "miscalibrated_b", "full"] {
        let config = presets::load(name).unwrap();
        let calibration = CameraCalibration::of(&config).unwrap();
        let (dp, dyaw) = prediction_error(&config, &calibration);
        let fit = calibration.fit.as_ref().unwrap();
        let (shift, turn) = fit.base_in_world.distance_to(&Pose::identity());
        eprintln!(
            "{name}: fitted error {:.1} mm at the base origin, {:.2}°; prediction off by ≤ {:.2} mm, {:.3}°",
            shift * 1e3,
            turn.to_degrees(),
            dp * 1e3,
            dyaw.to_degrees()
        );
        // Eight touches, each off by up to 1 mm per axis: the prediction within 1.5 touch errors.
        assert!(dp < 1.5 * TOUCH_ERROR * 3f64.sqrt(), "{name}: {dp}");
        assert!(dyaw < 0.3f64.to_radians(), "{name}: {dyaw}");
        if name == "full" {
            assert!(
                turn < 0.3f64.to_radians(),
                "{name}: a turn of {turn} rad where none is"
            );
        } else {
            // The cells' cameras are turned by 2° and 2.5°.
            assert!(turn > 1.5f64.to_radians(), "{name}: {turn}");
        }
    }
}

fn success(config: &EnvConfig, policy: &mut dyn Policy, episodes: usize) -> EvalReport {
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let results = scenario_set(config, 7, episodes)
        .unwrap()
        .iter()
        .map(|s| run_episode(&mut env, policy, s, None).unwrap())
        .collect();
    EvalReport::from_results(results)
}

#[test]
fn the_calibrated_script_grasps_where_the_open_loop_script_misses() {
    for name in ["miscalibrated", "miscalibrated_b"] {
        let config = presets::load(name).unwrap();
        let open = success(
            &config,
            &mut ScriptedGrasp::new(&config, BaselineConfig::default()),
            60,
        );
        let calibration = CameraCalibration::of(&config).unwrap();
        let calibrated = success(
            &config,
            &mut CalibratedScript::new(&config, calibration),
            60,
        );
        eprintln!(
            "{name}: open loop {:.3}, script + calibration {:.3} ({:?})",
            open.success_rate, calibrated.success_rate, calibrated.outcomes
        );
        assert!(open.success_rate <= 0.8, "{name}: {}", open.success_rate);
        assert!(
            calibrated.success_rate >= 0.95,
            "{name}: {:?}",
            calibrated.outcomes
        );
    }
}

#[test]
fn where_the_error_changes_every_episode_the_calibration_is_refused_and_nothing_corrected() {
    for name in ["hard", "wrist_camera"] {
        let config = presets::load(name).unwrap();
        let calibration = CameraCalibration::of(&config).unwrap();
        let why = calibration.fit.clone().unwrap_err();
        assert!(why.contains("beyond the bound"), "{name}: {why}");
        let mut env = TaskEnv::new(config.clone()).unwrap();
        let mut open = ScriptedGrasp::new(&config, BaselineConfig::default());
        let mut calibrated = CalibratedScript::new(&config, calibration);
        for s in scenario_set(&config, 7, 20).unwrap() {
            let a = run_episode(&mut env, &mut open, &s, None).unwrap();
            let b = run_episode(&mut env, &mut calibrated, &s, None).unwrap();
            assert_eq!(
                (a.outcome, a.steps),
                (b.outcome, b.steps),
                "{name}: scenario {}",
                s.seed
            );
        }
    }
}
