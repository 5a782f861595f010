//! Generalised advantage estimation (Schulman et al. 2016), as CleanRL computes it, with
//! truncation handled by bootstrapping from the value of the episode's final observation.
//!
//! Storage is `[step][env]`, flattened step-major: index `t * n_envs + e`.

/// Advantages and returns of one rollout.
#[derive(Clone, Debug, PartialEq)]
pub struct Gae {
    /// `A_t`, one per step and env.
    pub advantages: Vec<f32>,
    /// `R_t = A_t + V(s_t)`: the value targets.
    pub returns: Vec<f32>,
}

/// `δ_t = r_t + γ·V(s_{t+1})·(1 − terminal_t) − V(s_t)`, `A_t = δ_t + γλ·(1 − done_t)·A_{t+1}`.
///
/// - `rewards`, `values`: per step and env.
/// - `terminated`: the episode ended in a true terminal state after step t (no bootstrap).
/// - `truncated`: the episode was cut after step t (time limit): bootstrap from
///   `final_values[t * n_envs + e]`, the value of the last observation, but do not carry the
///   advantage across the reset.
/// - `next_values`: `V` of the observation after the rollout's last step, per env.
#[allow(clippy::too_many_arguments)]
pub fn compute_gae(
    n_envs: usize,
    rewards: &[f32],
    values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    final_values: &[f32],
    next_values: &[f32],
    gamma: f32,
    lambda: f32,
) -> Gae {
    let mut advantages = vec![0.0f32; rewards.len()];
    let mut returns = vec![0.0f32; rewards.len()];
    compute_gae_into(
        n_envs,
        rewards,
        values,
        terminated,
        truncated,
        final_values,
        next_values,
        gamma,
        lambda,
        &mut advantages,
        &mut returns,
    );
    Gae {
        advantages,
        returns,
    }
}

/// [`compute_gae`] into caller-owned `advantages` and `returns` (one per step and env).
///
/// # Panics
/// If the per-sample slices do not all have the same length, a multiple of `n_envs` (a
/// programming error: PPO's rollout buffer sizes them together).
#[allow(clippy::too_many_arguments)]
pub fn compute_gae_into(
    n_envs: usize,
    rewards: &[f32],
    values: &[f32],
    terminated: &[bool],
    truncated: &[bool],
    final_values: &[f32],
    next_values: &[f32],
    gamma: f32,
    lambda: f32,
    advantages: &mut [f32],
    returns: &mut [f32],
) {
    let n = rewards.len();
    assert!(
        n_envs > 0
            && n.is_multiple_of(n_envs)
            && values.len() == n
            && terminated.len() == n
            && truncated.len() == n
            && final_values.len() == n
            && advantages.len() == n
            && returns.len() == n,
        "GAE needs one value, flag, advantage and return per sample"
    );
    let steps = n / n_envs;
    for (e, &bootstrap) in next_values.iter().enumerate().take(n_envs) {
        let mut last = 0.0f32;
        for t in (0..steps).rev() {
            let i = t * n_envs + e;
            let next_value = if terminated[i] {
                0.0
            } else if truncated[i] {
                final_values[i]
            } else if t + 1 < steps {
                values[i + n_envs]
            } else {
                bootstrap
            };
            let delta = rewards[i] + gamma * next_value - values[i];
            let carry = if terminated[i] || truncated[i] {
                0.0
            } else {
                gamma * lambda * last
            };
            last = delta + carry;
            advantages[i] = last;
        }
    }
    for ((r, a), v) in returns.iter_mut().zip(&*advantages).zip(values) {
        *r = a + v;
    }
}

/// Normalises advantages to zero mean and unit standard deviation (ε = 1e-8).
pub fn normalize(advantages: &mut [f32]) {
    let n = advantages.len() as f32;
    if n < 2.0 {
        return;
    }
    let mean = advantages.iter().sum::<f32>() / n;
    let var = advantages.iter().map(|a| (a - mean).powi(2)).sum::<f32>() / (n - 1.0);
    let std = var.sqrt() + 1e-8;
    for a in advantages {
        *a = (*a - mean) / std;
    }
}

/// Explained variance `1 − Var(R − V) / Var(R)` (1 = perfect value function, ≤ 0 = useless).
pub fn explained_variance(values: &[f32], returns: &[f32]) -> f32 {
    let n = returns.len() as f32;
    let var = |x: &[f32]| {
        let m = x.iter().sum::<f32>() / n;
        x.iter().map(|v| (v - m).powi(2)).sum::<f32>() / n
    };
    let diff: Vec<f32> = returns.iter().zip(values).map(|(r, v)| r - v).collect();
    let var_r = var(returns);
    if var_r == 0.0 {
        f32::NAN
    } else {
        1.0 - var(&diff) / var_r
    }
}
