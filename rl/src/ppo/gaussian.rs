//! The policy's action distribution: a diagonal Gaussian `N(mean, exp(log_std)²)`.
//!
//! [`log_prob`] is the one log-probability of the crate: the rollout stores it for the sampled
//! actions and the update recomputes it for the same actions, so on the first minibatch of an
//! update (parameters not yet changed) the PPO ratio `exp(logπ_new − logπ_old)` is 1.

use burn::tensor::Tensor;

/// `½·ln(2π)`, computed in `f32`.
fn half_log_2pi() -> f32 {
    0.5 * (2.0 * std::f32::consts::PI).ln()
}

/// Log-density `[batch]` of `actions` `[batch, act_dim]` under `N(mean, exp(log_std)²)`
/// (`mean` `[batch, act_dim]`, `log_std` `[act_dim]`), summed over the action dimensions:
/// `Σ_d −½·((a_d − μ_d)/σ_d)² − ln σ_d − ½·ln(2π)`.
pub fn log_prob(mean: Tensor<2>, log_std: Tensor<1>, actions: Tensor<2>) -> Tensor<1> {
    let [batch, act_dim] = mean.dims();
    let log_std = log_std.unsqueeze_dim::<2>(0).expand([batch, act_dim]);
    let z = actions.sub(mean).div(log_std.clone().exp());
    z.powi_scalar(2)
        .mul_scalar(-0.5)
        .sub(log_std)
        .sub_scalar(half_log_2pi())
        .sum_dim(1)
        .squeeze_dim(1)
}

/// Entropy `[batch]` of the distribution with `log_std` `[act_dim]`, repeated for `batch` rows:
/// `Σ_d ln σ_d + ½ + ½·ln(2π)`.
pub fn entropy(log_std: Tensor<1>, batch: usize) -> Tensor<1> {
    let [act_dim] = log_std.dims();
    log_std
        .unsqueeze_dim::<2>(0)
        .expand([batch, act_dim])
        .add_scalar(0.5 + half_log_2pi())
        .sum_dim(1)
        .squeeze_dim(1)
}
