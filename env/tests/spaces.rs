//! The published spaces: every observation a rollout produces lies inside the observation
//! space, whose bounds are all finite.

use fairgrasp_env::config::{ArmSimulation, RandomizationConfig};
use fairgrasp_env::env::obs::{OBS_DIM, OBS_NAMES};
use fairgrasp_env::env::spaces::{ACT_DIM, action_space, observation_space};
use fairgrasp_env::{Action, EnvConfig, Observation, TaskEnv};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn flat(obs: &Observation) -> Vec<f64> {
    obs.to_array().iter().map(|v| *v as f64).collect()
}

#[test]
fn the_spaces_name_every_entry_with_finite_bounds() {
    let cfg = EnvConfig::default();
    let env = TaskEnv::new(cfg.clone()).unwrap();
    let obs = observation_space(&cfg, env.model());
    assert_eq!(obs.len(), OBS_DIM);
    assert_eq!(obs.names, OBS_NAMES.to_vec());
    assert_eq!(obs.units.len(), OBS_DIM);
    for i in 0..OBS_DIM {
        assert!(obs.low[i].is_finite() && obs.high[i].is_finite() && obs.low[i] < obs.high[i]);
    }
    let act = action_space();
    assert_eq!((act.len(), act.low[0], act.high[6]), (ACT_DIM, -1.0, 1.0));
    let tcp = fairgrasp_env::env::spaces::action_space_of(fairgrasp_env::config::ActionSpace::Tcp);
    assert_eq!(tcp.names[3], "tcp_yaw_rate");
    assert_eq!(tcp.units[0], "tcp_speed·m/s");
    assert_eq!((tcp.len(), tcp.names[6]), (ACT_DIM, "gripper"));
}

#[test]
fn random_rollouts_on_both_arm_models_stay_inside_the_observation_space() {
    for arm in [ArmSimulation::Servo, ArmSimulation::Multibody] {
        let mut cfg = EnvConfig {
            randomization: RandomizationConfig::full(),
            ..EnvConfig::default()
        };
        cfg.arm.model = arm;
        cfg.arm.action_scale = 3.0; // fast joints: the velocity bounds are tested
        let mut env = TaskEnv::new(cfg.clone()).unwrap();
        let space = observation_space(&cfg, env.model());
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut steps = 0;
        for episode in 0..6 {
            let (mut obs, _) = env.reset(episode).unwrap();
            loop {
                if let Some((i, v)) = space.first_outside(&flat(&obs)) {
                    panic!("{arm:?}: {} = {v} outside the space", OBS_NAMES[i]);
                }
                let a = Action(std::array::from_fn(|_| rng.random_range(-1.0..=1.0)));
                let step = env.step(&a).unwrap();
                obs = step.obs;
                steps += 1;
                if step.terminated || step.truncated {
                    break;
                }
            }
        }
        assert!(steps > 100, "{arm:?}: {steps} steps");
    }
}
