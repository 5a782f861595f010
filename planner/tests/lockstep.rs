//! Running the four scripts in lockstep (one simulation while their actions agree, what
//! `fairgrasp compare` does) gives every script the episode it gets alone, record for record:
//! on `sector`, where three of them agree on every scenario, and on `wrist_camera` and `nudged`,
//! where they part on most (those that part are simulated again, in lockstep among themselves:
//! on `nudged` the oracle follows the closed-loop script).

use fairgrasp_env::config::presets;
use fairgrasp_env::episode::{Policy, run_episode, run_lockstep};
use fairgrasp_env::scenario::scenario_set;
use fairgrasp_env::{EnvConfig, TaskEnv};
use fairgrasp_planner::{
    BaselineConfig, CalibratedScript, CameraCalibration, ClosedLoopGrasp, ScriptedGrasp,
};

/// The comparison's four scripts for `config`, in its order.
fn scripts(config: &EnvConfig) -> Vec<Box<dyn Policy>> {
    let calibration = CameraCalibration::of(config).unwrap();
    vec![
        Box::new(ScriptedGrasp::new(config, BaselineConfig::default())),
        Box::new(ClosedLoopGrasp::observed(config)),
        Box::new(ClosedLoopGrasp::oracle(config)),
        Box::new(CalibratedScript::new(config, calibration)),
    ]
}

/// Runs `episodes` scenarios of `preset` both ways; asserts equal records and returns how many
/// (scenario, follower) pairs shared the leader's episode.
fn lockstep_equals_alone(preset: &str, episodes: usize) -> usize {
    let config = presets::load(preset).unwrap();
    let scenarios = scenario_set(&config, 0, episodes).unwrap();
    let mut env = TaskEnv::new(config.clone()).unwrap();
    let (mut together, mut alone) = (scripts(&config), scripts(&config));
    let mut shared = 0;
    for (k, scenario) in scenarios.iter().enumerate() {
        let records = run_lockstep(&mut env, &mut together, scenario).unwrap();
        assert_eq!(records.len(), 4);
        let own: Vec<_> = alone
            .iter_mut()
            .map(|p| run_episode(&mut env, p, scenario, None).unwrap())
            .collect();
        for (m, (a, b)) in records.iter().zip(&own).enumerate() {
            assert_eq!(a, b, "{preset}, scenario {k}, script {m}");
        }
        shared += own[1..].iter().filter(|r| **r == own[0]).count();
    }
    shared
}

#[test]
fn scripts_in_lockstep_get_the_episodes_they_get_alone() {
    // `sector`: no imperfection; the closed-loop script and the oracle send the open-loop
    // script's actions on every scenario, the calibrated script (planning on its own estimate
    // of the camera) does not.
    assert_eq!(lockstep_equals_alone("sector", 6), 2 * 6);
    // `wrist_camera` and `nudged`: most followers part from the open-loop script (the
    // comparison's rows differ on most scenarios), so the runs alone are what is compared.
    let parted = lockstep_equals_alone("wrist_camera", 6) + lockstep_equals_alone("nudged", 6);
    assert!(parted < 2 * 3 * 6, "every follower agreed: nothing parted");
}
