//! The actor-critic: separate MLPs for the action mean and the value, a state-independent
//! log standard deviation, orthogonal initialisation (as SB3 and CleanRL do).
//!
//! Shapes: observations `[batch, obs_dim]`, actions `[batch, act_dim]`, values `[batch]`.

use std::collections::BTreeMap;

use burn::module::{Module, Param};
use burn::nn::{Initializer, Linear, LinearConfig};
use burn::tensor::{Device, Tensor, TensorData};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::ppo::gaussian;
use crate::ppo::init::orthogonal;

use fairgrasp_policy::actor::Actor;
use fairgrasp_policy::burnpack::Tensor as PlainTensor;

pub use fairgrasp_policy::checkpoint::network::{MAX_LAYERS, MAX_WIDTH, ModelConfig};

/// The ChaCha stream the initial weights are drawn from (PPO's sampling uses stream 0).
const INIT_STREAM: u64 = 1;

/// Actor and critic.
#[derive(Module, Debug)]
pub struct ActorCritic {
    actor: Vec<Linear>,
    critic: Vec<Linear>,
    /// Log standard deviation per action dimension.
    log_std: Param<Tensor<1>>,
}

fn mlp(
    sizes: &[usize],
    output_gain: f64,
    zero_output: bool,
    rng: &mut ChaCha8Rng,
    device: &Device,
) -> Vec<Linear> {
    let n = sizes.len() - 1;
    (0..n)
        .map(|i| {
            let last = i + 1 == n;
            // Zero weights and bias, then orthogonal weights drawn from the caller's generator
            // (burn's initialisers draw from the device's, shared by the whole process).
            let mut layer = LinearConfig::new(sizes[i], sizes[i + 1])
                .with_initializer(Initializer::Zeros)
                .init(device);
            if !(last && zero_output) {
                let gain = if last {
                    output_gain
                } else {
                    std::f64::consts::SQRT_2
                };
                // burn's `Linear` weight is `[d_input, d_output]`.
                let (rows, cols) = (sizes[i], sizes[i + 1]);
                let weights = orthogonal(rows, cols, gain, rng);
                layer.weight = Param::from_tensor(Tensor::from_data(
                    TensorData::new(weights, [rows, cols]),
                    device,
                ));
            }
            layer
        })
        .collect()
}

/// `tanh` from `exp` (burn 0.22's `tanh` is slow on CPU: ~27 ns per element): `1 − 2/(e^{2x} + 1)`.
fn fast_tanh<const D: usize>(x: Tensor<D>) -> Tensor<D> {
    let e = x.clamp(-15.0, 15.0).mul_scalar(2.0).exp();
    e.clone().sub_scalar(1.0).div(e.add_scalar(1.0))
}

fn forward_mlp(layers: &[Linear], x: Tensor<2>) -> Tensor<2> {
    let n = layers.len();
    let mut h = x;
    for (i, layer) in layers.iter().enumerate() {
        h = layer.forward(h);
        if i + 1 < n {
            h = fast_tanh(h);
        }
    }
    h
}

impl ActorCritic {
    /// A fresh network for `obs_dim` inputs and `act_dim` actions, its weights drawn from a
    /// generator seeded with `seed` (and owned by this call: the same seed gives the same
    /// network whatever else the process draws). Its stream is separate from the one PPO
    /// samples actions from with the same seed.
    pub fn new(
        obs_dim: usize,
        act_dim: usize,
        config: &ModelConfig,
        seed: u64,
        device: &Device,
    ) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(INIT_STREAM);
        let mut sizes = vec![obs_dim];
        sizes.extend(&config.hidden);
        let actor_sizes: Vec<usize> = sizes.iter().copied().chain([act_dim]).collect();
        let critic_sizes: Vec<usize> = sizes.iter().copied().chain([1]).collect();
        let mut actor = mlp(
            &actor_sizes,
            0.01,
            config.zero_actor_output,
            &mut rng,
            device,
        );
        if !config.actor_output_bias.is_empty()
            && let Some(last) = actor.last_mut()
        {
            // `ModelConfig::check` has made it one value per action entry.
            assert_eq!(
                config.actor_output_bias.len(),
                act_dim,
                "model.actor_output_bias"
            );
            last.bias = Some(Param::from_tensor(Tensor::from_data(
                TensorData::new(config.actor_output_bias.clone(), [act_dim]),
                device,
            )));
        }
        Self {
            actor,
            critic: mlp(&critic_sizes, 1.0, false, &mut rng, device),
            log_std: Param::from_tensor(Tensor::<1>::full([act_dim], config.log_std_init, device)),
        }
    }

    /// This network's actor and log-std with `other`'s critic (critic-only warm-up).
    pub fn with_critic_of(self, other: ActorCritic) -> Self {
        Self {
            critic: other.critic,
            ..self
        }
    }

    /// Mean action `[batch, act_dim]`.
    pub fn mean(&self, obs: Tensor<2>) -> Tensor<2> {
        forward_mlp(&self.actor, obs)
    }

    /// State value `[batch]`.
    pub fn value(&self, obs: Tensor<2>) -> Tensor<1> {
        forward_mlp(&self.critic, obs).squeeze_dim(1)
    }

    /// Log standard deviation `[act_dim]`.
    pub fn log_std(&self) -> Tensor<1> {
        self.log_std.val()
    }

    /// Log-probability `[batch]` of `actions` under the policy's Gaussian (summed over dims),
    /// and the distribution's entropy `[batch]`; both from [`crate::ppo::gaussian`].
    pub fn log_prob_and_entropy(
        &self,
        obs: Tensor<2>,
        actions: Tensor<2>,
    ) -> (Tensor<1>, Tensor<1>) {
        let mean = self.mean(obs);
        let [batch, _] = mean.dims();
        (
            gaussian::log_prob(mean, self.log_std(), actions),
            gaussian::entropy(self.log_std(), batch),
        )
    }

    /// Every parameter in a fixed order: per layer (actor's, then critic's) the weights
    /// row-major then the bias, and last the log-std.
    pub fn flat_parameters(&self) -> Vec<f32> {
        let mut out = Vec::new();
        let mut push = |t: Tensor<1>| out.extend(t.into_data().iter::<f32>());
        for layer in self.actor.iter().chain(&self.critic) {
            push(layer.weight.val().flatten::<1>(0, 1));
            if let Some(b) = &layer.bias {
                push(b.val());
            }
        }
        push(self.log_std());
        out
    }

    /// The actor's mean as the burn-free [`Actor`] that `eval`, `compare` and `replay` run: the
    /// same weights, read out of burn (`actor.<i>.weight` `[inputs, outputs]` row-major and
    /// `actor.<i>.bias`, as `model.bpk` stores them), so a policy acts alike in training's
    /// evaluations and after loading its checkpoint.
    pub fn plain_actor(&self) -> Actor {
        let mut tensors = BTreeMap::new();
        let mut sizes = Vec::with_capacity(self.actor.len() + 1);
        for (i, layer) in self.actor.iter().enumerate() {
            let [inputs, outputs] = layer.weight.dims();
            if i == 0 {
                sizes.push(inputs);
            }
            sizes.push(outputs);
            let weight = layer.weight.val().into_data().iter::<f32>().collect();
            let bias = match &layer.bias {
                Some(b) => b.val().into_data().iter::<f32>().collect(),
                None => vec![0.0; outputs],
            };
            let mut insert = |part: &str, shape: Vec<usize>, values: Vec<f32>| {
                let tensor = PlainTensor { shape, values };
                tensors.insert(format!("actor.{i}.{part}"), tensor);
            };
            insert("weight", vec![inputs, outputs], weight);
            insert("bias", vec![outputs], bias);
        }
        Actor::from_tensors(&tensors, &sizes).expect("the actor's own layers fit its sizes")
    }

    /// Are all parameters (weights, biases, log-std) finite? A diverged update makes them NaN
    /// or infinite; such a network must not be saved over a good checkpoint.
    pub fn parameters_finite(&self) -> bool {
        self.flat_parameters().iter().all(|v| v.is_finite())
    }
}
