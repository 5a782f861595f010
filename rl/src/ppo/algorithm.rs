//! PPO (Schulman et al. 2017), readable top to bottom like CleanRL's `ppo_continuous_action.py`:
//! rollout → GAE → epochs × minibatches of the clipped-surrogate loss → Adam.
//!
//! Storage is one preallocated flat buffer per quantity ([`RolloutBuffer`]: `obs`, `actions`,
//! `logprobs`, `rewards`, `terminated`, `truncated`, `values`, `advantages`, `returns`);
//! minibatches gather the rows they index (`mb_*` tensors), as CleanRL's `b_obs[mb_inds]`.
//! One log-probability ([`crate::ppo::gaussian::log_prob`]) serves the rollout and the update.
//! Where this follows SB3 rather than CleanRL: the optional `target_kl` stop (checked per
//! minibatch) and observation normalisation (`VecNormalize`'s running statistics).

use std::ops::Range;

use burn::grad_clipping::GradientClippingConfig;
use burn::module::Module;
use burn::optim::{AdamConfig, GradientsParams, ModuleOptimizer};
use burn::tensor::{Device, Tensor, TensorData};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::Serialize;

use crate::ppo::error::PpoError;
use crate::ppo::error::finite_output;
use crate::ppo::gae::{explained_variance, normalize};
use crate::ppo::gaussian;
use crate::ppo::loss::{RatioDiagnostics, clipped_surrogate, ratio_diagnostics, value_loss};
use crate::ppo::model::ActorCritic;
use crate::ppo::normalizer::RunningNorm;
use crate::ppo::rollout::{RolloutBuffer, RolloutShape, gather, gather_rows};
use crate::ppo::teacher::Kickstart;
use crate::ppo::vec_api::{EpisodeStats, StepBatch, VecEnvError, VecEnvironment, check_finite};

use crate::ppo::config::PpoConfig;

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
    /// Largest `|r − 1|` of the PPO ratio on the update's first minibatch, before any gradient
    /// step: 0 when the rollout and the update compute the same log-probability.
    pub first_ratio_deviation: f32,
    /// The kickstarting term before its weight ([`crate::ppo::teacher`]), mean over the
    /// minibatches; 0 without teachers.
    pub kickstart_loss: f32,
}

fn tensor1(values: Vec<f32>, device: &Device) -> Tensor<1> {
    let n = values.len();
    Tensor::from_data(TensorData::new(values, [n]), device)
}

/// A `[rows, cols]` tensor from row-major `values` (`rows · cols` of them).
fn tensor2(values: Vec<f32>, cols: usize, device: &Device) -> Tensor<2> {
    let rows = values.len() / cols.max(1);
    Tensor::from_data(TensorData::new(values, [rows, cols]), device)
}

fn to_vec<const D: usize>(t: Tensor<D>) -> Result<Vec<f32>, PpoError> {
    t.into_data()
        .try_to_vec::<f32>()
        .map_err(|e| PpoError::Tensor(format!("{e:?}")))
}

fn scalar(t: Tensor<1>) -> Result<f32, PpoError> {
    Ok(to_vec(t)?.first().copied().unwrap_or(f32::NAN))
}

/// A new Adam optimiser with PPO's gradient-norm clipping.
pub fn adam(config: &PpoConfig) -> ModuleOptimizer {
    AdamConfig::new()
        .with_epsilon(1e-5)
        .with_grad_clipping(Some(GradientClippingConfig::Norm(config.max_grad_norm)))
        .init()
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
    /// The raw policy inputs the next rollout starts from, `[env][obs_dim]` (empty: reset).
    next_obs: Vec<f32>,
    /// The rollout storage, kept between iterations.
    buffer: Option<RolloutBuffer>,
    /// Teachers whose mean actions the policy is also pulled towards (None: plain PPO).
    pub kickstart: Option<Kickstart>,
    /// The teachers' labels of the rollout's samples, `[sample][act_dim]`, and which entries
    /// they label (1) or not (0).
    teacher_targets: Vec<f32>,
    teacher_mask: Vec<f32>,
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
            next_obs: Vec::new(),
            buffer: None,
            kickstart: None,
            teacher_targets: Vec::new(),
            teacher_mask: Vec::new(),
        }
    }

    /// Normalises the raw `[env][dim]` rows `raw` into `out`, row by row.
    fn normalize_rows(&self, raw: &[f32], dim: usize, out: &mut [f32]) {
        for (o, r) in out.chunks_mut(dim.max(1)).zip(raw.chunks(dim.max(1))) {
            self.obs_norm.normalize_into(r, o);
        }
    }

    /// Values `[rows]` of normalised inputs `[rows][dim]`, without gradients.
    fn values_of(
        inference: &ActorCritic,
        obs_n: Vec<f32>,
        dim: usize,
        device: &Device,
    ) -> Result<Vec<f32>, PpoError> {
        to_vec(inference.value(tensor2(obs_n, dim, device)))
    }

    /// Fills the rollout buffer with `n_steps` steps of every env.
    fn collect<E: VecEnvironment>(&mut self, env: &mut E) -> Result<RolloutBuffer, PpoError> {
        let shape = RolloutShape {
            n_steps: self.config.n_steps,
            n_envs: env.n_envs(),
            obs_dim: env.obs_dim(),
            act_dim: env.act_dim(),
        };
        let mut b = self.buffer_for(shape);
        self.start_observations(env, &shape)?;
        let device = self.device.clone().inner();
        let inference = self.model.valid();
        b.episodes.clear();
        if self.kickstart.is_some() {
            self.teacher_targets
                .resize(shape.samples() * shape.act_dim, 0.0);
            self.teacher_mask
                .resize(shape.samples() * shape.act_dim, 0.0);
        }
        for t in 0..shape.n_steps {
            let rows = b.step_range(t);
            self.sample_actions(&inference, &mut b, rows.clone(), &device)?;
            let actions = &b.actions[rows.start * shape.act_dim..rows.end * shape.act_dim];
            let step = env.step(actions)?;
            step.check_shape(shape.n_envs, shape.obs_dim)?;
            self.record_step(&inference, &mut b, rows, step, &device)?;
        }
        self.bootstrap_next_values(&inference, &mut b, &device)?;
        Ok(b)
    }

    /// The kept rollout buffer if it has `shape`, else a new one (and a reset of the envs).
    fn buffer_for(&mut self, shape: RolloutShape) -> RolloutBuffer {
        match self.buffer.take() {
            Some(b) if b.shape == shape => b,
            _ => {
                self.next_obs.clear();
                RolloutBuffer::new(shape)
            }
        }
    }

    /// Resets the envs when there are no observations to continue from.
    fn start_observations<E: VecEnvironment>(
        &mut self,
        env: &mut E,
        shape: &RolloutShape,
    ) -> Result<(), PpoError> {
        let expected = shape.n_envs * shape.obs_dim;
        if self.next_obs.len() == expected {
            return Ok(());
        }
        let first = env.reset()?;
        if first.len() != expected {
            return Err(VecEnvError::Shape {
                what: "observation",
                expected,
                got: first.len(),
            }
            .into());
        }
        self.next_obs.clear();
        self.next_obs.extend_from_slice(first);
        Ok(())
    }

    /// For the samples `rows` (one step of every env): the normalised observations (after the
    /// statistics take them in), the teachers' labels, the values, the actions sampled around
    /// the policy's mean and their log-probabilities.
    fn sample_actions(
        &mut self,
        inference: &ActorCritic,
        b: &mut RolloutBuffer,
        rows: Range<usize>,
        device: &Device,
    ) -> Result<(), PpoError> {
        let (od, ad) = (b.shape.obs_dim, b.shape.act_dim);
        check_finite(&self.next_obs, od, "observation")?;
        if self.config.norm_obs {
            self.obs_norm.update_rows(&self.next_obs);
        }
        let obs_n = &mut b.obs[rows.start * od..rows.end * od];
        self.normalize_rows(&self.next_obs, od, obs_n);
        if let Some(k) = &self.kickstart {
            let labels = rows.start * ad..rows.end * ad;
            k.label_step(
                &self.next_obs,
                od,
                ad,
                &mut self.teacher_targets[labels.clone()],
                &mut self.teacher_mask[labels],
            );
        }
        let x = tensor2(obs_n.to_vec(), od, device);
        let mean_t = inference.mean(x.clone());
        let mean = to_vec(mean_t.clone())?;
        let values = to_vec(inference.value(x))?;
        let log_std_t = inference.log_std();
        let log_std = to_vec(log_std_t.clone())?;
        finite_output(&mean, ad, "mean action")?;
        finite_output(&values, 1, "value")?;
        let actions = &mut b.actions[rows.start * ad..rows.end * ad];
        for (k, a) in actions.iter_mut().enumerate() {
            let z: f32 = StandardNormal.sample(&mut self.rng);
            *a = mean[k] + log_std[k % ad].exp() * z;
        }
        finite_output(actions, ad, "sampled action")?;
        let logprob = gaussian::log_prob(mean_t, log_std_t, tensor2(actions.to_vec(), ad, device));
        for (slot, v) in b.logprobs[rows.clone()].iter_mut().zip(to_vec(logprob)?) {
            *slot = v;
        }
        b.values[rows].copy_from_slice(&values);
        Ok(())
    }

    /// Stores what the envs' step gave for the samples `rows`: the bootstrap values of ended
    /// episodes' last observations, rewards, flags and finished episodes; the step's
    /// observations are where the next one starts.
    fn record_step(
        &mut self,
        inference: &ActorCritic,
        b: &mut RolloutBuffer,
        rows: Range<usize>,
        step: &StepBatch,
        device: &Device,
    ) -> Result<(), PpoError> {
        let (n_envs, od) = (b.shape.n_envs, b.shape.obs_dim);
        let ended: Vec<usize> = (0..n_envs).filter(|&e| step.ended(e)).collect();
        b.final_values[rows.clone()].fill(0.0);
        if !ended.is_empty() {
            let raw = gather_rows(&step.final_obs, od, &ended);
            check_finite(&raw, od, "final observation")?;
            let mut finals = vec![0.0; raw.len()];
            self.normalize_rows(&raw, od, &mut finals);
            let final_values = Self::values_of(inference, finals, od, device)?;
            for (&e, v) in ended.iter().zip(final_values) {
                b.final_values[rows.start + e] = v;
            }
        }
        b.rewards[rows.clone()].copy_from_slice(&step.rewards);
        b.terminated[rows.clone()].copy_from_slice(&step.terminated);
        b.truncated[rows].copy_from_slice(&step.truncated);
        b.episodes.extend(step.finished.iter().flatten());
        self.next_obs.copy_from_slice(&step.obs);
        Ok(())
    }

    /// The values of the observations the rollout ends on (GAE bootstraps from them).
    fn bootstrap_next_values(
        &self,
        inference: &ActorCritic,
        b: &mut RolloutBuffer,
        device: &Device,
    ) -> Result<(), PpoError> {
        let od = b.shape.obs_dim;
        check_finite(&self.next_obs, od, "observation")?;
        let mut obs_n = vec![0.0; self.next_obs.len()];
        self.normalize_rows(&self.next_obs, od, &mut obs_n);
        let next_values = Self::values_of(inference, obs_n, od, device)?;
        finite_output(&next_values, 1, "value")?;
        b.next_values.copy_from_slice(&next_values);
        Ok(())
    }

    /// One PPO iteration: a rollout of `n_steps` per env, then the update. `progress` in
    /// [0, 1] is the fraction of training done (for the learning-rate schedule).
    pub fn iterate<E: VecEnvironment>(
        &mut self,
        env: &mut E,
        progress: f64,
    ) -> Result<UpdateStats, PpoError> {
        let c = self.config.clone();
        let mut b = self.collect(env)?;
        b.compute_advantages(c.gamma, c.gae_lambda);
        let lr = c.learning_rate_at(progress);
        let mut b_inds: Vec<usize> = (0..b.shape.samples()).collect();
        let mut stats = UpdateStats {
            learning_rate: lr,
            episodes: b.episodes.clone(),
            ..UpdateStats::default()
        };
        let (mut count, mut sums) = (0.0f32, [0.0f32; 6]);
        let kick_weight = self.kickstart.as_ref().map(|k| k.weight_at(progress));
        'epochs: for _ in 0..c.n_epochs {
            b_inds.shuffle(&mut self.rng);
            for mb_inds in b_inds.chunks(c.batch_size) {
                let (terms, diagnostics) = self.minibatch_update(&b, mb_inds, lr, kick_weight)?;
                if count == 0.0 {
                    stats.first_ratio_deviation = diagnostics.max_deviation;
                }
                for (s, v) in sums.iter_mut().zip(terms) {
                    *s += v;
                }
                count += 1.0;
                // SB3's early stop; a non-finite KL (a ratio overflowed) stops the epochs too.
                let kl = diagnostics.approx_kl;
                if c.target_kl.is_some_and(|t| !kl.is_finite() || kl > t) {
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
            stats.kickstart_loss,
        ] = sums.map(|s| s / count.max(1.0));
        stats.explained_variance = explained_variance(&b.values, &b.returns);
        self.buffer = Some(b);
        self.check_divergence(&stats)?;
        Ok(stats)
    }

    /// One gradient step on the minibatch `mb_inds` of the rollout: PPO's clipped surrogate,
    /// value loss and entropy bonus, plus the kickstart term when teachers pull (`kick_weight`).
    /// Returns the terms averaged into [`UpdateStats`] (policy loss, value loss, entropy,
    /// approximate KL, clip fraction, kickstart loss) and the ratio diagnostics.
    fn minibatch_update(
        &mut self,
        b: &RolloutBuffer,
        mb_inds: &[usize],
        lr: f64,
        kick_weight: Option<f32>,
    ) -> Result<([f32; 6], RatioDiagnostics), PpoError> {
        let c = &self.config;
        let (od, ad) = (b.shape.obs_dim, b.shape.act_dim);
        let mb_obs = tensor2(gather_rows(&b.obs, od, mb_inds), od, &self.device);
        let mb_actions = tensor2(gather_rows(&b.actions, ad, mb_inds), ad, &self.device);
        let mut mb_adv = gather(&b.advantages, mb_inds);
        if c.norm_adv {
            normalize(&mut mb_adv);
        }
        let (new_logprob, entropy) = self.model.log_prob_and_entropy(mb_obs.clone(), mb_actions);
        let (pg_loss, log_ratio) = clipped_surrogate(
            new_logprob,
            tensor1(gather(&b.logprobs, mb_inds), &self.device),
            tensor1(mb_adv, &self.device),
            c.clip_coef,
        );
        let new_values = self.model.value(mb_obs.clone());
        let v_loss = value_loss(
            new_values,
            tensor1(gather(&b.returns, mb_inds), &self.device),
            tensor1(gather(&b.values, mb_inds), &self.device),
            c.clip_vloss.then_some(c.clip_coef),
        );
        let entropy = entropy.mean();
        let mut loss = pg_loss
            .clone()
            .sub(entropy.clone().mul_scalar(c.ent_coef))
            .add(v_loss.clone().mul_scalar(c.vf_coef));
        let mut kick_loss = 0.0;
        if let Some(w) = kick_weight {
            let term = self.kickstart_term(mb_obs, mb_inds, ad);
            kick_loss = scalar(term.clone().inner())?;
            loss = loss.add(term.mul_scalar(w));
        }
        // Diagnostics (no gradients).
        let diagnostics = ratio_diagnostics(&to_vec(log_ratio.inner())?, c.clip_coef);
        let grads = GradientsParams::from_grads(loss.backward(), &self.model);
        self.model = self.optimizer.step(lr, self.model.clone(), grads);
        let terms = [
            scalar(pg_loss.inner())?,
            scalar(v_loss.inner())?,
            scalar(entropy.inner())?,
            diagnostics.approx_kl,
            diagnostics.clip_fraction,
            kick_loss,
        ];
        Ok((terms, diagnostics))
    }

    /// The kickstart term of a minibatch: the squared distance of the policy's mean from the
    /// teachers' labels, over the labelled entries, per sample.
    fn kickstart_term(&self, mb_obs: Tensor<2>, mb_inds: &[usize], ad: usize) -> Tensor<1> {
        let target = gather_rows(&self.teacher_targets, ad, mb_inds);
        let mask = gather_rows(&self.teacher_mask, ad, mb_inds);
        let diff = self
            .model
            .mean(mb_obs)
            .sub(tensor2(target, ad, &self.device));
        diff.clone()
            .mul(diff)
            .mul(tensor2(mask, ad, &self.device))
            .sum()
            .div_scalar(mb_inds.len() as f32)
    }

    /// Divergence: a non-finite loss or parameter. The KL and the clip fraction are
    /// diagnostics, reported as they are.
    fn check_divergence(&self, stats: &UpdateStats) -> Result<(), PpoError> {
        let losses = [
            ("policy loss", stats.policy_loss),
            ("value loss", stats.value_loss),
            ("entropy", stats.entropy),
            ("kickstart loss", stats.kickstart_loss),
        ];
        if let Some((what, value)) = losses.into_iter().find(|(_, v)| !v.is_finite()) {
            return Err(PpoError::NonFiniteLoss { what, value });
        }
        if !self.model.parameters_finite() {
            return Err(PpoError::NonFiniteParameters);
        }
        Ok(())
    }

    /// The deterministic (mean) action for a raw policy input.
    pub fn mean_action(&self, obs: &[f32]) -> Result<Vec<f32>, PpoError> {
        let inference = self.model.valid();
        let o = self.obs_norm.normalize(obs);
        to_vec(inference.mean(tensor2(o, obs.len(), &self.device.clone().inner())))
    }
}
