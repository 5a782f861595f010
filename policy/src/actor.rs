//! The policy network's actor as plain arrays: the deterministic (mean) action of a trained
//! policy, computed without burn. The same network as `rl`'s `ActorCritic::mean`: linear layers
//! `x·W + b` (`W` is `[inputs, outputs]`, row-major, as burn stores it) with tanh between them,
//! tanh computed as burn's model computes it (`(e − 1)/(e + 1)`, `e = exp(2·clamp(x, ±15))`).
//! Tests in `rl/tests/inference.rs` hold it to burn's forward pass.

use std::collections::BTreeMap;

use crate::burnpack::Tensor;

/// One linear layer: `outputs` values from `inputs`.
#[derive(Clone, Debug, PartialEq)]
struct Layer {
    inputs: usize,
    outputs: usize,
    /// `[inputs][outputs]`, row-major.
    weight: Vec<f32>,
    bias: Vec<f32>,
}

/// The actor MLP.
#[derive(Clone, Debug, PartialEq)]
pub struct Actor {
    layers: Vec<Layer>,
}

/// The tanh of burn's model, in f32.
fn tanh(x: f32) -> f32 {
    let e = (x.clamp(-15.0, 15.0) * 2.0).exp();
    (e - 1.0) / (e + 1.0)
}

impl Actor {
    /// The actor of a network with `sizes` = `[input, hidden…, actions]`, from its tensors
    /// (`actor.<i>.weight`, `actor.<i>.bias`); every shape is checked against `sizes`.
    pub fn from_tensors(
        tensors: &BTreeMap<String, Tensor>,
        sizes: &[usize],
    ) -> Result<Actor, String> {
        let mut layers = Vec::new();
        for (i, pair) in sizes.windows(2).enumerate() {
            let (inputs, outputs) = (pair[0], pair[1]);
            let get = |part: &str, shape: Vec<usize>| {
                let name = format!("actor.{i}.{part}");
                let t = tensors
                    .get(&name)
                    .ok_or_else(|| format!("no tensor `{name}`"))?;
                if t.shape != shape {
                    return Err(format!(
                        "`{name}` has shape {:?}, the network needs {shape:?}",
                        t.shape
                    ));
                }
                Ok(t.values.clone())
            };
            layers.push(Layer {
                inputs,
                outputs,
                weight: get("weight", vec![inputs, outputs])?,
                bias: get("bias", vec![outputs])?,
            });
        }
        if tensors.contains_key(&format!("actor.{}.weight", layers.len())) {
            return Err(format!(
                "the file has more actor layers than the {} the network needs",
                layers.len()
            ));
        }
        Ok(Actor { layers })
    }

    /// The input size.
    pub fn inputs(&self) -> usize {
        self.layers.first().map_or(0, |l| l.inputs)
    }

    /// The mean action for one (normalised) input of [`Actor::inputs`] values.
    pub fn mean(&self, input: &[f32]) -> Vec<f32> {
        let mut x = input.to_vec();
        let last = self.layers.len().saturating_sub(1);
        for (i, layer) in self.layers.iter().enumerate() {
            let mut y = layer.bias.clone();
            // Σ_k x_k·W_kj accumulated in k order, then + b_j.
            let mut acc = vec![0.0f32; layer.outputs];
            for (k, &xk) in x.iter().enumerate().take(layer.inputs) {
                let row = &layer.weight[k * layer.outputs..(k + 1) * layer.outputs];
                for (a, &w) in acc.iter_mut().zip(row) {
                    *a += xk * w;
                }
            }
            for (v, a) in y.iter_mut().zip(acc) {
                *v += a;
                if i < last {
                    *v = tanh(*v);
                }
            }
            x = y;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tensor(shape: Vec<usize>, values: Vec<f32>) -> Tensor {
        Tensor { shape, values }
    }

    #[test]
    fn a_two_layer_actor_matches_a_hand_computation() {
        // 2 → 2 (tanh) → 1. W0 = [[1, 0], [0, 2]] (inputs × outputs), b0 = [0, 0.5];
        // W1 = [[1], [-1]], b1 = [0.25].
        let mut t = BTreeMap::new();
        t.insert(
            "actor.0.weight".into(),
            tensor(vec![2, 2], vec![1.0, 0.0, 0.0, 2.0]),
        );
        t.insert("actor.0.bias".into(), tensor(vec![2], vec![0.0, 0.5]));
        t.insert("actor.1.weight".into(), tensor(vec![2, 1], vec![1.0, -1.0]));
        t.insert("actor.1.bias".into(), tensor(vec![1], vec![0.25]));
        let actor = Actor::from_tensors(&t, &[2, 2, 1]).unwrap();
        let x = [0.3f32, -0.2];
        let h = [0.3f64.tanh(), (-0.4f64 + 0.5).tanh()];
        let expected = h[0] - h[1] + 0.25;
        assert!((f64::from(actor.mean(&x)[0]) - expected).abs() < 1e-6);
        // A wrong shape or a missing layer is refused by name.
        let e = Actor::from_tensors(&t, &[3, 2, 1]).unwrap_err();
        assert!(e.contains("actor.0.weight") && e.contains("[3, 2]"), "{e}");
        let e = Actor::from_tensors(&t, &[2, 2, 2, 1]).unwrap_err();
        assert!(e.contains("actor.1.weight"), "{e}");
        let e = Actor::from_tensors(&t, &[2, 2]).unwrap_err();
        assert!(e.contains("more actor layers"), "{e}");
    }

    #[test]
    fn the_tanh_is_bounded_and_odd_and_saturates_without_nan() {
        for x in [-100.0f32, -3.0, -0.5, 0.0, 0.5, 3.0, 100.0] {
            let t = tanh(x);
            assert!(t.abs() <= 1.0 && (t + tanh(-x)).abs() < 1e-7, "{x}: {t}");
            assert!((t - x.tanh()).abs() < 1e-6, "{x}: {t} vs {}", x.tanh());
        }
    }
}
