//! PPO (Schulman et al. 2017), readable top to bottom like CleanRL's `ppo_continuous_action.py`:
//! rollout → GAE → epochs × minibatches of the clipped-surrogate loss → Adam.
//!
//! Storage is named after the quantity (`obs`, `actions`, `logprobs`, `rewards`, `values`,
//! `terminated`, `truncated`); batch views are `b_*`, minibatch tensors `mb_*`.

use burn::grad_clipping::GradientClippingConfig;
use burn::module::Module;
use burn::optim::{AdamConfig, GradientsParams, ModuleOptimizer};
use burn::tensor::{Device, Tensor, TensorData};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::Serialize;

use crate::gae::{compute_gae, explained_variance, normalize};
use crate::model::ActorCritic;
use crate::normalizer::RunningNorm;
use crate::vec_api::{EpisodeStats, VecEnvironment};

pub use crate::ppo_config::{PpoConfig, PpoConfigError};

/// Diagnostics of one update, as CleanRL logs them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct UpdateStats {
    pub policy_loss: f32,
    pub value_loss: f32,
    pub entropy: f32,
    pub approx_kl: f32,
    pub clip_fraction: f32,
    pub explained_variance: f32,
    pub learning_rate: f64,
    /// Episodes that finished during the rollout.
    pub episodes: Vec<EpisodeStats>,
}

/// The clipped surrogate objective, as a loss `[1]`: `mean(max(−A·r, −A·clip(r, 1−ε, 1+ε)))`
/// with `r = exp(logπ_new − logπ_old)`. Also returns `r` for the diagnostics.
pub fn clipped_surrogate(
    new_logprob: Tensor<1>,
    old_logprob: Tensor<1>,
    advantages: Tensor<1>,
    clip: f32,
) -> (Tensor<1>, Tensor<1>) {
    let ratio = new_logprob.sub(old_logprob).exp();
    let pg1 = advantages.clone().neg().mul(ratio.clone());
    let pg2 = advantages
        .neg()
        .mul(ratio.clone().clamp(1.0 - clip, 1.0 + clip));
    (pg1.max_pair(pg2).mean(), ratio)
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

fn tensor1(values: &[f32], device: &Device) -> Tensor<1> {
    Tensor::from_data(TensorData::new(values.to_vec(), [values.len()]), device)
}

fn tensor2(rows: &[Vec<f32>], device: &Device) -> Tensor<2> {
    let cols = rows.first().map_or(0, Vec::len);
    let flat: Vec<f32> = rows.iter().flatten().copied().collect();
    Tensor::from_data(TensorData::new(flat, [rows.len(), cols]), device)
}

fn to_vec<const D: usize>(t: Tensor<D>) -> Vec<f32> {
    t.into_data().try_to_vec::<f32>().expect("f32 tensor")
}

/// A new Adam optimiser with PPO's gradient-norm clipping.
pub fn adam(config: &PpoConfig) -> ModuleOptimizer {
    AdamConfig::new()
        .with_epsilon(1e-5)
        .with_grad_clipping(Some(GradientClippingConfig::Norm(config.max_grad_norm)))
        .init()
}

/// One rollout: `[step][env]` flattened step-major.
struct Rollout {
    obs: Vec<Vec<f32>>,
    actions: Vec<Vec<f32>>,
    logprobs: Vec<f32>,
    rewards: Vec<f32>,
    values: Vec<f32>,
    terminated: Vec<bool>,
    truncated: Vec<bool>,
    final_values: Vec<f32>,
    next_values: Vec<f32>,
    episodes: Vec<EpisodeStats>,
}

/// PPO state: the model, its optimiser, observation statistics and the sampling RNG.
pub struct Ppo {
    pub config: PpoConfig,
    pub model: ActorCritic,
    pub obs_norm: RunningNorm,
    pub optimizer: ModuleOptimizer,
    /// The autodiff device the model trains on.
    pub device: Device,
    rng: ChaCha8Rng,
    /// The observation the next rollout starts from, per env (raw).
    next_obs: Option<Vec<Vec<f32>>>,
}

impl Ppo {
    /// PPO for `model` (on an autodiff `device`), sampling with `seed`.
    pub fn new(
        config: PpoConfig,
        model: ActorCritic,
        obs_norm: RunningNorm,
        device: Device,
        seed: u64,
    ) -> Self {
        let optimizer = adam(&config);
        Self {
            config,
            model,
            obs_norm,
            optimizer,
            device,
            rng: ChaCha8Rng::seed_from_u64(seed),
            next_obs: None,
        }
    }

    /// Mean and log-std for raw observations, without gradients.
    fn act_batch(
        &self,
        inference: &ActorCritic,
        obs_n: &[Vec<f32>],
    ) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
        let device = self.device.clone().inner();
        let x = tensor2(obs_n, &device);
        let mean = to_vec(inference.mean(x.clone()));
        let values = to_vec(inference.value(x));
        let log_std = to_vec(inference.log_std());
        (mean, log_std, values)
    }

    fn collect<E: VecEnvironment>(&mut self, env: &mut E) -> Rollout {
        let n_envs = env.n_envs();
        let act_dim = env.act_dim();
        let mut obs = self.next_obs.take().unwrap_or_else(|| env.reset());
        let inference = self.model.valid();
        let mut r = Rollout {
            obs: Vec::new(),
            actions: Vec::new(),
            logprobs: Vec::new(),
            rewards: Vec::new(),
            values: Vec::new(),
            terminated: Vec::new(),
            truncated: Vec::new(),
            final_values: Vec::new(),
            next_values: Vec::new(),
            episodes: Vec::new(),
        };
        let half_log_2pi = 0.5 * (2.0 * std::f32::consts::PI).ln();
        for _ in 0..self.config.n_steps {
            if self.config.norm_obs {
                self.obs_norm.update(&obs);
            }
            let obs_n: Vec<Vec<f32>> = obs.iter().map(|o| self.obs_norm.normalize(o)).collect();
            let (mean, log_std, values) = self.act_batch(&inference, &obs_n);
            let mut actions = Vec::with_capacity(n_envs);
            for e in 0..n_envs {
                let mut action = Vec::with_capacity(act_dim);
                let mut logprob = 0.0;
                for d in 0..act_dim {
                    let z: f32 = StandardNormal.sample(&mut self.rng);
                    action.push(mean[e * act_dim + d] + log_std[d].exp() * z);
                    logprob += -0.5 * z * z - log_std[d] - half_log_2pi;
                }
                r.logprobs.push(logprob);
                actions.push(action);
            }
            let step = env.step(&actions);
            // Bootstrap values of truncated episodes' last observations.
            let finals: Vec<Vec<f32>> = step
                .final_obs
                .iter()
                .flatten()
                .map(|o| self.obs_norm.normalize(o))
                .collect();
            let final_values = if finals.is_empty() {
                Vec::new()
            } else {
                self.act_batch(&inference, &finals).2
            };
            let mut k = 0;
            for f in &step.final_obs {
                r.final_values.push(if f.is_some() {
                    k += 1;
                    final_values[k - 1]
                } else {
                    0.0
                });
            }
            r.obs.extend(obs_n);
            r.actions.extend(actions);
            r.values.extend(values);
            r.rewards.extend(&step.rewards);
            r.terminated.extend(&step.terminated);
            r.truncated.extend(&step.truncated);
            r.episodes.extend(step.finished.iter().flatten());
            obs = step.obs;
        }
        let obs_n: Vec<Vec<f32>> = obs.iter().map(|o| self.obs_norm.normalize(o)).collect();
        r.next_values = self.act_batch(&inference, &obs_n).2;
        self.next_obs = Some(obs);
        r
    }

    /// One PPO iteration: a rollout of `n_steps` per env, then the update. `progress` in
    /// [0, 1] is the fraction of training done (for the learning-rate schedule).
    pub fn iterate<E: VecEnvironment>(&mut self, env: &mut E, progress: f64) -> UpdateStats {
        let c = self.config.clone();
        let r = self.collect(env);
        let gae = compute_gae(
            env.n_envs(),
            &r.rewards,
            &r.values,
            &r.terminated,
            &r.truncated,
            &r.final_values,
            &r.next_values,
            c.gamma,
            c.gae_lambda,
        );
        let lr = if c.anneal_lr {
            c.learning_rate * (1.0 - progress).max(0.0)
        } else {
            c.learning_rate
        };
        let n = r.rewards.len();
        let mut b_inds: Vec<usize> = (0..n).collect();
        let mut stats = UpdateStats {
            learning_rate: lr,
            episodes: r.episodes.clone(),
            ..UpdateStats::default()
        };
        let (mut count, mut sums) = (0.0f32, [0.0f32; 5]);
        'epochs: for _ in 0..c.n_epochs {
            b_inds.shuffle(&mut self.rng);
            for mb_inds in b_inds.chunks(c.batch_size) {
                let pick = |v: &[f32]| mb_inds.iter().map(|&i| v[i]).collect::<Vec<f32>>();
                let mb_obs = tensor2(
                    &mb_inds
                        .iter()
                        .map(|&i| r.obs[i].clone())
                        .collect::<Vec<_>>(),
                    &self.device,
                );
                let mb_actions = tensor2(
                    &mb_inds
                        .iter()
                        .map(|&i| r.actions[i].clone())
                        .collect::<Vec<_>>(),
                    &self.device,
                );
                let mut mb_adv = pick(&gae.advantages);
                if c.norm_adv {
                    normalize(&mut mb_adv);
                }
                let (new_logprob, entropy) =
                    self.model.log_prob_and_entropy(mb_obs.clone(), mb_actions);
                let (pg_loss, ratio) = clipped_surrogate(
                    new_logprob.clone(),
                    tensor1(&pick(&r.logprobs), &self.device),
                    tensor1(&mb_adv, &self.device),
                    c.clip_coef,
                );
                let new_values = self.model.value(mb_obs);
                let v_loss = value_loss(
                    new_values,
                    tensor1(&pick(&gae.returns), &self.device),
                    tensor1(&pick(&r.values), &self.device),
                    c.clip_vloss.then_some(c.clip_coef),
                );
                let entropy = entropy.mean();
                let loss = pg_loss
                    .clone()
                    .sub(entropy.clone().mul_scalar(c.ent_coef))
                    .add(v_loss.clone().mul_scalar(c.vf_coef));
                // Diagnostics (no gradients).
                let ratio = to_vec(ratio.inner());
                let approx_kl =
                    ratio.iter().map(|r| (r - 1.0) - r.ln()).sum::<f32>() / ratio.len() as f32;
                let clip_frac = ratio
                    .iter()
                    .filter(|r| (*r - 1.0).abs() > c.clip_coef)
                    .count() as f32
                    / ratio.len() as f32;
                let grads = GradientsParams::from_grads(loss.backward(), &self.model);
                self.model = self.optimizer.step(lr, self.model.clone(), grads);
                for (s, v) in sums.iter_mut().zip([
                    to_vec(pg_loss.inner())[0],
                    to_vec(v_loss.inner())[0],
                    to_vec(entropy.inner())[0],
                    approx_kl,
                    clip_frac,
                ]) {
                    *s += v;
                }
                count += 1.0;
                if c.target_kl.is_some_and(|t| approx_kl > t) {
                    break 'epochs;
                }
            }
        }
        [
            stats.policy_loss,
            stats.value_loss,
            stats.entropy,
            stats.approx_kl,
            stats.clip_fraction,
        ] = sums.map(|s| s / count.max(1.0));
        stats.explained_variance = explained_variance(&r.values, &gae.returns);
        stats
    }

    /// The deterministic (mean) action for a raw observation.
    pub fn mean_action(&self, obs: &[f32]) -> Vec<f32> {
        let inference = self.model.valid();
        let o = self.obs_norm.normalize(obs);
        self.act_batch(&inference, &[o]).0
    }
}
