//! Weight initialisation from a generator the caller owns.
//!
//! burn's initialisers draw from the device's generator, which every network and thread of the
//! process shares: two trainings in one process would then draw each other's numbers and the
//! seed would no longer decide the result. These functions take the run's own generator.

use rand::Rng;
use rand_distr::StandardNormal;

/// A `rows × cols` matrix (row-major) with orthonormal columns (`rows ≥ cols`) or orthonormal
/// rows (`rows < cols`), scaled by `gain`: the orthogonal initialisation of Saxe et al. (2014)
/// that SB3 and CleanRL use. A Gaussian matrix is orthonormalised by modified Gram–Schmidt (in
/// `f64`); each column keeps the sign of its projection onto the Gaussian draw, as the QR
/// construction with `sign(diag(R))` does, so the result is uniformly distributed.
pub fn orthogonal(rows: usize, cols: usize, gain: f64, rng: &mut impl Rng) -> Vec<f32> {
    // Orthonormalise the `k` columns of a tall `n × k` Gaussian matrix, then lay it out as
    // `rows × cols` (transposed when the wanted matrix is wide).
    let (n, k) = (rows.max(cols), rows.min(cols));
    let mut q: Vec<Vec<f64>> = (0..k)
        .map(|_| {
            (0..n)
                .map(|_| rng.sample::<f64, _>(StandardNormal))
                .collect()
        })
        .collect();
    for j in 0..k {
        let (done, rest) = q.split_at_mut(j);
        let column = &mut rest[0];
        for previous in done.iter() {
            let dot: f64 = previous.iter().zip(column.iter()).map(|(a, b)| a * b).sum();
            for (c, p) in column.iter_mut().zip(previous) {
                *c -= dot * p;
            }
        }
        let norm = column.iter().map(|c| c * c).sum::<f64>().sqrt();
        // A Gaussian column lies in the span of the previous ones with probability 0; guard
        // against the impossible rather than divide by zero.
        let norm = if norm > 1e-12 { norm } else { 1.0 };
        for c in column.iter_mut() {
            *c /= norm;
        }
    }
    let mut out = vec![0.0f32; rows * cols];
    for (j, column) in q.iter().enumerate() {
        for (i, value) in column.iter().enumerate() {
            let (r, c) = if rows >= cols { (i, j) } else { (j, i) };
            out[r * cols + c] = (gain * value) as f32;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// `A·Aᵀ` (`wide`) or `Aᵀ·A` for a row-major `rows × cols` matrix.
    fn gram(a: &[f32], rows: usize, cols: usize, wide: bool) -> Vec<f64> {
        let (n, len) = if wide { (rows, cols) } else { (cols, rows) };
        let at = |v: usize, i: usize| {
            if wide {
                a[v * cols + i] as f64
            } else {
                a[i * cols + v] as f64
            }
        };
        let mut g = vec![0.0; n * n];
        for x in 0..n {
            for y in 0..n {
                g[x * n + y] = (0..len).map(|i| at(x, i) * at(y, i)).sum();
            }
        }
        g
    }

    #[test]
    fn tall_and_wide_matrices_are_orthogonal_times_the_gain() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for (rows, cols, gain) in [(40, 8, 1.0), (8, 40, 2.0f64.sqrt()), (16, 16, 0.01)] {
            let w = orthogonal(rows, cols, gain, &mut rng);
            let g = gram(&w, rows, cols, rows < cols);
            let n = rows.min(cols);
            for x in 0..n {
                for y in 0..n {
                    let expected = if x == y { gain * gain } else { 0.0 };
                    assert!(
                        (g[x * n + y] - expected).abs() < 1e-5 * gain.max(1.0),
                        "{rows}×{cols}: G[{x}][{y}] = {}",
                        g[x * n + y]
                    );
                }
            }
        }
    }

    #[test]
    fn the_same_generator_state_gives_the_same_matrix_and_another_a_different_one() {
        let a = orthogonal(6, 4, 1.0, &mut ChaCha8Rng::seed_from_u64(1));
        let b = orthogonal(6, 4, 1.0, &mut ChaCha8Rng::seed_from_u64(1));
        let c = orthogonal(6, 4, 1.0, &mut ChaCha8Rng::seed_from_u64(2));
        assert_eq!(a, b);
        assert_ne!(a, c);
    }
}
