//! PPO: the losses against hand computations, config refusals, and learning a small task.

use burn::tensor::{Device, Tensor, TensorData};
use fairgrasp_rl::agent::grasp_agent::ACT_DIM;
use fairgrasp_rl::ppo::free_env::FreeEnv;
use fairgrasp_rl::ppo::model::{ActorCritic, ModelConfig};
use fairgrasp_rl::ppo::normalizer::RunningNorm;
use fairgrasp_rl::ppo::point_mass::{HORIZON, PointMass};
use fairgrasp_rl::ppo::vec_api::VecEnvironment;
use fairgrasp_rl::ppo::{
    Ppo, PpoConfig, PpoConfigError, clipped_surrogate, ratio_diagnostics, value_loss,
};

fn t1(v: &[f32]) -> Tensor<1> {
    Tensor::from_data(TensorData::new(v.to_vec(), [v.len()]), &Device::flex())
}

fn scalar(t: Tensor<1>) -> f32 {
    t.into_data().try_to_vec::<f32>().unwrap()[0]
}

#[test]
fn the_clipped_surrogate_matches_a_hand_computation() {
    // Ratios e^{0.5} = 1.6487 (clipped to 1.2), e^{-0.5} = 0.6065 (clipped to 0.8), 1.
    let new = t1(&[0.5, -0.5, 0.0]);
    let old = t1(&[0.0, 0.0, 0.0]);
    let adv = t1(&[1.0, 1.0, -2.0]);
    let (loss, log_ratio) = clipped_surrogate(new, old, adv, 0.2);
    let lr: Vec<f32> = log_ratio.into_data().try_to_vec().unwrap();
    assert_eq!(lr, vec![0.5, -0.5, 0.0]);
    // Per sample max(−A·r, −A·clip(r)): max(−1.6487, −1.2) = −1.2; max(−0.6065, −0.8) = −0.6065;
    // max(2, 2) = 2. Mean = (−1.2 − 0.6065 + 2)/3.
    let expected = (-1.2 - (-0.5f32).exp() + 2.0) / 3.0;
    assert!((scalar(loss) - expected).abs() < 1e-6);
}

#[test]
fn a_minibatch_whose_ratio_underflows_has_a_finite_kl_and_loss() {
    // logπ_new − logπ_old = −200: r = e^−200 underflows to 0 in f32, where the form
    // (r − 1) − ln r gives ∞. From the log-ratio: (e^−200 − 1) + 200 = 199 for that sample.
    let log_ratio = [-200.0f32, 0.0, 0.1];
    assert_eq!((-200.0f32).exp(), 0.0, "the premise: the ratio underflows");
    let d = ratio_diagnostics(&log_ratio, 0.2);
    let expected = (199.0 + 0.0 + (0.1f64.exp() - 1.0 - 0.1)) / 3.0;
    assert!(
        (f64::from(d.approx_kl) - expected).abs() < 1e-4,
        "{}",
        d.approx_kl
    );
    // The underflowed sample is clipped (|0 − 1| > 0.2), the others are not.
    assert!((d.clip_fraction - 1.0 / 3.0).abs() < 1e-6);
    assert!((d.max_deviation - 1.0).abs() < 1e-6);
    // The loss itself stays finite: the clipped term bounds it.
    let (loss, _) = clipped_surrogate(
        t1(&[-200.0, 0.0, 0.1]),
        t1(&[0.0, 0.0, 0.0]),
        t1(&[1.0, -1.0, 1.0]),
        0.2,
    );
    assert!(scalar(loss).is_finite());
    // An overflowing ratio is reported as what it is (an infinite KL), not hidden.
    assert_eq!(ratio_diagnostics(&[200.0], 0.2).approx_kl, f32::INFINITY);
}

#[test]
fn the_value_loss_matches_a_hand_computation_with_and_without_clipping() {
    let values = t1(&[1.0, 3.0]);
    let returns = t1(&[2.0, 0.0]);
    let old = t1(&[1.5, 1.0]);
    // Unclipped: ½·mean(1, 9) = 2.5.
    assert!(
        (scalar(value_loss(
            values.clone(),
            returns.clone(),
            old.clone(),
            None
        )) - 2.5)
            .abs()
            < 1e-6
    );
    // Clipped (ε 0.2): V_c = (1.3, 1.2); (V_c − R)² = (0.49, 1.44); max with (1, 9) = (1, 9): 2.5.
    // With ε 0.2 and returns far from the clip region the max keeps the unclipped terms.
    assert!((scalar(value_loss(values, returns, old, Some(0.2))) - 2.5).abs() < 1e-6);
    let values = t1(&[2.0]);
    let returns = t1(&[1.0]);
    let old = t1(&[0.0]);
    // Unclipped (2−1)² = 1; clipped V_c = 0.2, (0.2−1)² = 0.64; max = 1 → 0.5.
    assert!(
        (scalar(value_loss(
            values.clone(),
            returns.clone(),
            old.clone(),
            Some(0.2)
        )) - 0.5)
            .abs()
            < 1e-6
    );
    let returns = t1(&[3.0]);
    // Unclipped (2−3)² = 1; clipped (0.2−3)² = 7.84; max = 7.84 → 3.92.
    assert!((scalar(value_loss(values, returns, old, Some(0.2))) - 3.92).abs() < 1e-5);
}

#[test]
fn a_rollout_that_is_not_a_multiple_of_the_batch_size_is_refused() {
    let config = PpoConfig {
        n_steps: 100,
        batch_size: 64,
        ..PpoConfig::default()
    };
    let err = config.validate(1).unwrap_err();
    assert!(matches!(
        err,
        PpoConfigError::UnevenMinibatches { rollout: 100, .. }
    ));
    assert!(err.to_string().contains("batch_size 64"), "{err}");
    assert!(
        PpoConfig {
            n_steps: 128,
            ..config
        }
        .validate(1)
        .is_ok()
    );
    assert!(PpoConfig::default().validate(1).is_ok(), "SB3's 2048 / 64");
}

#[test]
fn the_learning_rate_holds_until_anneal_from_then_falls_linearly_to_zero() {
    let flat = PpoConfig {
        learning_rate: 1e-3,
        ..PpoConfig::default()
    };
    assert_eq!(flat.learning_rate_at(0.9), 1e-3, "no anneal_lr: constant");
    let from_start = PpoConfig {
        anneal_lr: true,
        ..flat.clone()
    };
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    assert!(close(from_start.learning_rate_at(0.0), 1e-3));
    assert!(close(from_start.learning_rate_at(0.25), 0.75e-3));
    let held = PpoConfig {
        anneal_from: 0.6,
        ..from_start
    };
    for (progress, rate) in [
        (0.0, 1e-3),
        (0.6, 1e-3),
        (0.8, 0.5e-3),
        (1.0, 0.0),
        (1.2, 0.0),
    ] {
        let got = held.learning_rate_at(progress);
        assert!(close(got, rate), "at {progress}: {got}, not {rate}");
    }
}

fn evaluate(ppo: &Ppo, episodes: usize) -> f32 {
    evaluate_with(&|o| ppo.mean_action(o).unwrap(), episodes)
}

fn evaluate_with(policy: &dyn Fn(&[f32]) -> Vec<f32>, episodes: usize) -> f32 {
    let mut env = PointMass::new(1, 999);
    let mut obs = env.reset().unwrap().to_vec();
    let mut total = 0.0;
    let mut done = 0;
    while done < episodes {
        let action = policy(&obs);
        let step = env.step(&action).unwrap();
        total += step.rewards[0];
        if step.truncated[0] {
            done += 1;
        }
        obs.copy_from_slice(&step.obs);
    }
    total / episodes as f32
}

#[test]
fn ppo_learns_to_drive_a_point_mass_to_its_goal() {
    let device = Device::flex().autodiff();
    let mut env = PointMass::new(8, 0);
    let config = PpoConfig {
        n_steps: 64,
        batch_size: 64,
        n_epochs: 10,
        learning_rate: 3e-3,
        gamma: 0.95,
        ..PpoConfig::default()
    };
    config.validate(env.n_envs()).unwrap();
    let model = ActorCritic::new(2, 1, &ModelConfig::default(), 0, &device);
    let mut ppo = Ppo::new(config, model, RunningNorm::new(2, true), device, 0);
    let before = evaluate(&ppo, 20);
    let iterations = 60; // 60 × 64 × 8 = 30 720 env steps
    for k in 0..iterations {
        ppo.iterate(&mut env, k as f64 / iterations as f64).unwrap();
    }
    let after = evaluate(&ppo, 20);
    // The reference: the best saturated PD controller a = clip(−kp·x − kd·v) over a gain grid,
    // on the same 20 start states.
    let mut best_pd = f32::NEG_INFINITY;
    for kp in [1.0f32, 2.0, 4.0, 8.0, 16.0] {
        for kd in [0.5f32, 1.0, 2.0, 4.0, 8.0] {
            best_pd = best_pd.max(evaluate_with(
                &|o: &[f32]| vec![(-kp * o[0] - kd * o[1]).clamp(-1.0, 1.0)],
                20,
            ));
        }
    }
    // Printed in full precision: `.ci/run` runs this binary twice and the lines must agree.
    eprintln!(
        "return per episode: before {before:?}, after {after:?}, best PD {best_pd:?} (horizon {HORIZON})"
    );
    assert!(
        after >= 1.25 * best_pd,
        "PPO {after:.2} is not near the best PD controller {best_pd:.2} (before {before:.2})"
    );
}

/// PPO on `env` with a random actor (so actions and log-probabilities vary), seed 3.
fn ppo_for(env: &impl VecEnvironment, n_steps: usize) -> Ppo {
    let device = Device::flex().autodiff();
    let config = PpoConfig {
        n_steps,
        batch_size: 64,
        n_epochs: 2,
        learning_rate: 1e-3,
        ..PpoConfig::default()
    };
    config.validate(env.n_envs()).unwrap();
    let (obs_dim, act_dim) = (env.obs_dim(), env.act_dim());
    let model = ActorCritic::new(obs_dim, act_dim, &ModelConfig::default(), 3, &device);
    Ppo::new(config, model, RunningNorm::new(obs_dim, true), device, 3)
}

#[test]
fn the_ppo_ratio_is_exactly_one_on_the_first_minibatch_of_every_update() {
    // Before the first gradient step of an update the parameters are those that sampled the
    // rollout, and one log-probability function serves both: r = exp(logπ − logπ_old) = 1
    // exactly, on a 1-D and a 7-D action space, in the first update and after training moved
    // the network.
    let mut point_mass = PointMass::new(8, 1);
    let mut ppo = ppo_for(&point_mass, 32);
    for update in 0..3 {
        let stats = ppo.iterate(&mut point_mass, 0.0).unwrap();
        assert_eq!(
            stats.first_ratio_deviation, 0.0,
            "point mass, update {update}"
        );
        assert!(stats.approx_kl > 0.0, "the updates move the policy");
    }
    let mut free = FreeEnv::new(4, 30, ACT_DIM);
    assert_eq!(free.act_dim(), ACT_DIM);
    let mut ppo = ppo_for(&free, 32);
    for update in 0..3 {
        let stats = ppo.iterate(&mut free, 0.0).unwrap();
        assert_eq!(
            stats.first_ratio_deviation, 0.0,
            "7-D actions, update {update}"
        );
    }
}

#[test]
fn a_fresh_actor_starts_at_its_output_bias() {
    // With a zero output layer the mean action is the bias alone, on any input; with the usual
    // small output weights it is the bias plus a little. Without the field both start near 0.
    let device = Device::flex();
    let bias = vec![0.0, 0.25, 0.0, 0.0, 0.0, 0.0, -0.5];
    let obs = Tensor::<2>::from_data(
        TensorData::new(
            (0..3 * 5).map(|i| i as f32 - 7.0).collect::<Vec<f32>>(),
            [3, 5],
        ),
        &device,
    );
    // The fresh network's mean actions on `obs`, 3 rows of ACT_DIM.
    let mean_of = |config: &ModelConfig| {
        config.check().unwrap();
        let model = ActorCritic::new(5, ACT_DIM, config, 4, &device);
        let mean = model.mean(obs.clone()).into_data();
        mean.try_to_vec::<f32>().unwrap()
    };
    for zero in [true, false] {
        let plain = ModelConfig {
            zero_actor_output: zero,
            ..ModelConfig::default()
        };
        let biased = ModelConfig {
            actor_output_bias: bias.clone(),
            ..plain.clone()
        };
        for (k, m) in mean_of(&biased).iter().enumerate() {
            let tolerance = if zero { 0.0 } else { 0.1 };
            let want = bias[k % ACT_DIM];
            assert!(
                (m - want).abs() <= tolerance,
                "zero {zero}, entry {k}: {m}, not {want}"
            );
        }
        let gripper = mean_of(&plain)[6];
        assert!(gripper.abs() < 0.1, "no bias: gripper mean {gripper}");
    }
}
