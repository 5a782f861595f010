//! GAE against values computed by hand.

use fairgrasp_rl::ppo::gae::{compute_gae, explained_variance, normalize};

#[test]
fn gae_matches_a_hand_computation_on_one_env() {
    // Three steps, no episode end, bootstrap V = 0.5 after the last.
    let (g, l) = (0.9f32, 0.8f32);
    let rewards = [1.0, 0.0, 2.0];
    let values = [0.5, 1.0, 1.5];
    let out = compute_gae(
        1,
        &rewards,
        &values,
        &[false; 3],
        &[false; 3],
        &[0.0; 3],
        &[0.5],
        g,
        l,
    );
    let d2 = 2.0 + g * 0.5 - 1.5; // 0.95
    let d1 = 0.0 + g * 1.5 - 1.0; // 0.35
    let d0 = 1.0 + g * 1.0 - 0.5; // 1.4
    let a2 = d2;
    let a1 = d1 + g * l * a2;
    let a0 = d0 + g * l * a1;
    for (got, want) in out.advantages.iter().zip([a0, a1, a2]) {
        assert!((got - want).abs() < 1e-6, "{got} vs {want}");
    }
    for ((r, a), v) in out.returns.iter().zip(&out.advantages).zip(values) {
        assert!((r - a - v).abs() < 1e-6);
    }
}

#[test]
fn a_terminal_step_does_not_bootstrap_and_a_truncated_one_bootstraps_from_its_final_obs() {
    let (g, l) = (0.99f32, 0.95f32);
    // Two envs, two steps. Env 0 terminates at t=0; env 1 is truncated at t=0 (final V = 3).
    let rewards = [1.0, 1.0, 0.5, 0.5];
    let values = [2.0, 2.0, 1.0, 1.0];
    let terminated = [true, false, false, false];
    let truncated = [false, true, false, false];
    let final_values = [0.0, 3.0, 0.0, 0.0];
    let out = compute_gae(
        2,
        &rewards,
        &values,
        &terminated,
        &truncated,
        &final_values,
        &[4.0, 4.0],
        g,
        l,
    );
    // Step 1 (both envs): δ = 0.5 + γ·4 − 1.
    let a_last = 0.5 + g * 4.0 - 1.0;
    assert!((out.advantages[2] - a_last).abs() < 1e-6);
    assert!((out.advantages[3] - a_last).abs() < 1e-6);
    // Env 0, t=0: terminal: δ = 1 − 2, nothing carried.
    assert!((out.advantages[0] - (1.0 - 2.0)).abs() < 1e-6);
    // Env 1, t=0: truncated: δ = 1 + γ·3 − 2, nothing carried across the reset.
    assert!((out.advantages[1] - (1.0 + g * 3.0 - 2.0)).abs() < 1e-6);
}

#[test]
fn normalised_advantages_have_zero_mean_and_unit_std() {
    let mut a = vec![1.0, 2.0, 3.0, 10.0];
    normalize(&mut a);
    let mean: f32 = a.iter().sum::<f32>() / 4.0;
    let var: f32 = a.iter().map(|x| (x - mean).powi(2)).sum::<f32>() / 3.0;
    assert!(mean.abs() < 1e-6 && (var - 1.0).abs() < 1e-5);
}

#[test]
fn explained_variance_is_one_for_a_perfect_critic_and_zero_for_a_constant_one() {
    let returns = [1.0, 2.0, 3.0];
    assert!((explained_variance(&returns, &returns) - 1.0).abs() < 1e-6);
    assert!(explained_variance(&[2.0, 2.0, 2.0], &returns).abs() < 1e-6);
}
