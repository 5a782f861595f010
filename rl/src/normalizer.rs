//! Running mean and variance of observations (Welford / Chan's parallel update), as SB3's
//! `VecNormalize` does: observations are normalised and clipped to ±10 before the network.

use serde::{Deserialize, Serialize};

/// Per-dimension running statistics; saved in checkpoints.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunningNorm {
    pub mean: Vec<f64>,
    pub var: Vec<f64>,
    pub count: f64,
    /// Normalisation is the identity when false (statistics are still kept).
    pub enabled: bool,
}

impl RunningNorm {
    pub fn new(dim: usize, enabled: bool) -> Self {
        Self {
            mean: vec![0.0; dim],
            var: vec![1.0; dim],
            count: 1e-4,
            enabled,
        }
    }

    /// Folds a batch of observations into the statistics.
    pub fn update(&mut self, batch: &[Vec<f32>]) {
        if batch.is_empty() {
            return;
        }
        let n = batch.len() as f64;
        for d in 0..self.mean.len() {
            let mean_b = batch.iter().map(|o| o[d] as f64).sum::<f64>() / n;
            let var_b = batch
                .iter()
                .map(|o| (o[d] as f64 - mean_b).powi(2))
                .sum::<f64>()
                / n;
            let delta = mean_b - self.mean[d];
            let total = self.count + n;
            self.mean[d] += delta * n / total;
            let m2 = self.var[d] * self.count + var_b * n + delta * delta * self.count * n / total;
            self.var[d] = m2 / total;
        }
        self.count += n;
    }

    /// `clip((o − mean)/sqrt(var + 1e-8), ±10)`.
    pub fn normalize(&self, obs: &[f32]) -> Vec<f32> {
        if !self.enabled {
            return obs.to_vec();
        }
        obs.iter()
            .enumerate()
            .map(|(d, &o)| {
                (((o as f64 - self.mean[d]) / (self.var[d] + 1e-8).sqrt()).clamp(-10.0, 10.0))
                    as f32
            })
            .collect()
    }
}
