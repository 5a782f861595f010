//! The scripted baseline: success on the easy presets, limits respected, clear IK failures,
//! reproducible outcomes.

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{EvalReport, Outcome, run_episode};
use fairgrasp_env::scenario::{Scenario, scenario_set};
use fairgrasp_env::{EnvConfig, HOME_JOINTS, TaskEnv};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};

fn evaluate(config: &EnvConfig, seed: u64, n: usize) -> EvalReport {
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(config, seed, n).unwrap();
    let mut policy = ScriptedGrasp::new(config, BaselineConfig::default());
    let results = scenarios
        .iter()
        .map(|s| run_episode(&mut env, &mut policy, s, None).unwrap())
        .collect();
    EvalReport::from_results(results)
}

#[test]
fn baseline_succeeds_on_at_least_95_percent_of_the_fixed_and_sector_presets() {
    for preset in ["fixed", "sector"] {
        let config = presets::load(preset).unwrap();
        let report = evaluate(&config, 1, 100);
        eprintln!(
            "{preset}: {:.2} ({:?})",
            report.success_rate, report.outcomes
        );
        assert!(
            report.success_rate >= 0.95,
            "{preset}: {:.2}, {:?}",
            report.success_rate,
            report.outcomes
        );
    }
}

#[test]
fn the_same_seed_gives_the_same_outcomes() {
    let config = presets::load("full").unwrap();
    let a = evaluate(&config, 5, 6);
    let b = evaluate(&config, 5, 6);
    assert_eq!(a.results, b.results);
}

#[test]
fn an_unreachable_object_is_an_ik_failure_not_a_panic() {
    let mut config = EnvConfig::default();
    config.scene.table_size = [3.0, 3.0];
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let far = Scenario {
        seed: 0,
        object_xy: [1.2, 0.0],
        object_yaw: 0.0,
        friction: 0.8,
        mass: 0.1,
        start_joints: HOME_JOINTS,
        observed_position_error: [0.0; 3],
        observed_yaw_error: 0.0,
        nudge: None,
        camera_offset: None,
        fixture: None,
    };
    let mut policy = ScriptedGrasp::new(&config, BaselineConfig::default());
    let result = run_episode(&mut env, &mut policy, &far, None).unwrap();
    assert_eq!(result.outcome, Outcome::IkFailure);
}

#[test]
fn planned_trajectories_stay_within_the_fr3_velocity_and_acceleration_limits() {
    let config = presets::load("sector").unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let scenarios = scenario_set(&config, 3, 10).unwrap();
    let model = env.model().clone();
    let mut policy = ScriptedGrasp::new(&config, BaselineConfig::default());
    let limits = *policy.limits();
    for i in 0..6 {
        assert!(limits.max_velocity[i] <= model.joints[i].max_velocity);
        assert!(
            limits.max_velocity[i] <= config.arm.action_scale,
            "the action range bounds the speed"
        );
        assert!(limits.max_acceleration[i] <= config.arm.max_acceleration);
    }
    let mut checked = 0;
    for s in &scenarios {
        let (mut obs, _) = env.reset_to(s);
        fairgrasp_env::episode::Policy::reset(&mut policy, s.seed);
        for _ in 0..200 {
            let action = fairgrasp_env::episode::Policy::act(&mut policy, &obs);
            if let Some(traj) = policy.trajectory() {
                let n = 200;
                for k in 0..=n {
                    let (_, v, a) = traj.sample(traj.duration() * k as f64 / n as f64);
                    for i in 0..6 {
                        assert!(
                            v[i].abs() <= limits.max_velocity[i] + 1e-9,
                            "joint {i}: {} rad/s",
                            v[i]
                        );
                        assert!(
                            a[i].abs() <= limits.max_acceleration[i] + 1e-9,
                            "joint {i}: {} rad/s²",
                            a[i]
                        );
                    }
                }
                checked += 1;
            }
            // The script never asks for the whole action range: the trajectories use
            // `velocity_fraction` of it and the feedback term stays within the headroom, so no
            // joint command is clipped (a clipped command would leave the plan behind).
            for (i, a) in action.0[..6].iter().enumerate() {
                assert!(a.abs() < 1.0, "joint {i} command saturated: {a}");
            }
            let step = env.step(&action).unwrap();
            obs = step.obs;
            if step.terminated || step.truncated {
                break;
            }
        }
    }
    assert!(checked > 0);
}
