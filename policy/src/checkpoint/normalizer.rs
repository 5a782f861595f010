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
        self.fold(batch.len(), |k| &batch[k]);
    }

    /// Folds a batch of observations stored flat, `[row][dim]`, into the statistics.
    pub fn update_rows(&mut self, rows: &[f32]) {
        let dim = self.mean.len().max(1);
        self.fold(rows.len() / dim, |k| &rows[k * dim..(k + 1) * dim]);
    }

    /// Chan's parallel update with the `n` rows `row(0) … row(n − 1)`.
    fn fold<'a>(&mut self, n: usize, row: impl Fn(usize) -> &'a [f32]) {
        if n == 0 {
            return;
        }
        let count = n as f64;
        for d in 0..self.mean.len() {
            let value = |k: usize| row(k).get(d).map_or(0.0, |&v| v as f64);
            let mean_b = (0..n).map(value).sum::<f64>() / count;
            let var_b = (0..n).map(|k| (value(k) - mean_b).powi(2)).sum::<f64>() / count;
            let delta = mean_b - self.mean[d];
            let total = self.count + count;
            self.mean[d] += delta * count / total;
            let m2 = self.var[d] * self.count
                + var_b * count
                + delta * delta * self.count * count / total;
            self.var[d] = m2 / total;
        }
        self.count += count;
    }

    /// `clip((o − mean)/sqrt(var + 1e-8), ±10)`.
    pub fn normalize(&self, obs: &[f32]) -> Vec<f32> {
        let mut out = vec![0.0; obs.len()];
        self.normalize_into(obs, &mut out);
        out
    }

    /// [`RunningNorm::normalize`] into `out` (the first `min(len)` values; nothing allocated).
    pub fn normalize_into(&self, obs: &[f32], out: &mut [f32]) {
        if !self.enabled {
            out.iter_mut().zip(obs).for_each(|(o, &v)| *o = v);
            return;
        }
        for (d, (o, &v)) in out.iter_mut().zip(obs).enumerate() {
            let (mean, var) = (
                self.mean.get(d).copied().unwrap_or(0.0),
                self.var.get(d).copied().unwrap_or(1.0),
            );
            *o = ((v as f64 - mean) / (var + 1e-8).sqrt()).clamp(-10.0, 10.0) as f32;
        }
    }
}
