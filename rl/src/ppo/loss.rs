//! PPO's losses and the diagnostics of its ratio, each in one function: the clipped surrogate,
//! the (optionally clipped) value loss, and the approximate KL and clip fraction from the
//! log-ratio. Shapes: `[batch]` per-sample tensors in, `[1]` losses out.

use burn::tensor::Tensor;

/// The clipped surrogate objective, as a loss `[1]`: `mean(max(−A·r, −A·clip(r, 1−ε, 1+ε)))`
/// with `r = exp(logπ_new − logπ_old)`. Also returns the log-ratio `logπ_new − logπ_old` for
/// the diagnostics ([`ratio_diagnostics`]).
pub fn clipped_surrogate(
    new_logprob: Tensor<1>,
    old_logprob: Tensor<1>,
    advantages: Tensor<1>,
    clip: f32,
) -> (Tensor<1>, Tensor<1>) {
    let log_ratio = new_logprob.sub(old_logprob);
    let ratio = log_ratio.clone().exp();
    let pg1 = advantages.clone().neg().mul(ratio.clone());
    let pg2 = advantages.neg().mul(ratio.clamp(1.0 - clip, 1.0 + clip));
    (pg1.max_pair(pg2).mean(), log_ratio)
}

/// What one minibatch's PPO ratios say about the update, computed from the log-ratios
/// `lr = logπ_new − logπ_old` (as CleanRL does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RatioDiagnostics {
    /// Schulman's low-variance estimator of KL(old ‖ new): `mean((e^lr − 1) − lr)`. From the
    /// log-ratio it stays finite when a ratio underflows to 0 (`lr` very negative), where the
    /// form `(r − 1) − ln r` gives `−ln 0 = ∞`.
    pub approx_kl: f32,
    /// The fraction of samples with `|r − 1| > ε` (the clipped ones).
    pub clip_fraction: f32,
    /// `max |r − 1|`.
    pub max_deviation: f32,
}

/// [`RatioDiagnostics`] of the log-ratios `log_ratio` with clip range `clip`; sums in `f64`.
pub fn ratio_diagnostics(log_ratio: &[f32], clip: f32) -> RatioDiagnostics {
    let n = log_ratio.len().max(1) as f64;
    let (mut kl, mut clipped, mut max_deviation) = (0.0f64, 0usize, 0.0f32);
    for &lr in log_ratio {
        let lr = f64::from(lr);
        let ratio = lr.exp();
        kl += lr.exp_m1() - lr;
        let deviation = (ratio - 1.0).abs();
        clipped += usize::from(deviation > f64::from(clip));
        max_deviation = max_deviation.max(deviation as f32);
    }
    RatioDiagnostics {
        approx_kl: (kl / n) as f32,
        clip_fraction: (clipped as f64 / n) as f32,
        max_deviation,
    }
}

/// The value loss `[1]`: `½·mean((V − R)²)`, or with clipping
/// `½·mean(max((V − R)², (V_old + clip(V − V_old, ±ε) − R)²))`.
pub fn value_loss(
    values: Tensor<1>,
    returns: Tensor<1>,
    old_values: Tensor<1>,
    clip: Option<f32>,
) -> Tensor<1> {
    let unclipped = values.clone().sub(returns.clone()).powi_scalar(2);
    match clip {
        None => unclipped.mean().mul_scalar(0.5),
        Some(c) => {
            let clipped = old_values
                .clone()
                .add(values.sub(old_values).clamp(-c, c))
                .sub(returns)
                .powi_scalar(2);
            unclipped.max_pair(clipped).mean().mul_scalar(0.5)
        }
    }
}
