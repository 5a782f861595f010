//! N environments stepped in parallel threads, with auto-reset and batched observations.
//!
//! Environment `i` draws the seed of its `k`-th episode as `base_seed + i · 1 000 000 + k`, so a
//! run is reproducible whatever the number of threads.

use crate::config::EnvConfig;
use crate::env::{Action, EnvError, GraspEnv, Info};
use crate::obs::{OBS_DIM, Observation};

/// One batched step.
#[derive(Clone, Debug)]
pub struct VecStep {
    /// Observation to act on next: after an auto-reset, the new episode's first one.
    pub obs: Vec<[f32; OBS_DIM]>,
    pub rewards: Vec<f64>,
    pub terminated: Vec<bool>,
    pub truncated: Vec<bool>,
    pub infos: Vec<Info>,
    /// The last observation of an episode that ended in this step (for bootstrapping).
    pub final_obs: Vec<Option<Observation>>,
}

/// Parallel environments with auto-reset.
pub struct VecEnv {
    envs: Vec<GraspEnv>,
    episodes: Vec<u64>,
    base_seed: u64,
    threads: usize,
}

fn seed_for(base: u64, env: usize, episode: u64) -> u64 {
    base.wrapping_add(env as u64 * 1_000_000)
        .wrapping_add(episode)
}

impl VecEnv {
    /// `n` environments of `config`, stepped on `threads` threads (at least 1).
    pub fn new(
        config: &EnvConfig,
        n: usize,
        threads: usize,
        base_seed: u64,
    ) -> Result<Self, EnvError> {
        let envs = (0..n.max(1))
            .map(|_| GraspEnv::new(config.clone()))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            episodes: vec![0; envs.len()],
            envs,
            base_seed,
            threads: threads.max(1),
        })
    }

    /// Number of environments.
    pub fn len(&self) -> usize {
        self.envs.len()
    }

    /// Always false: a VecEnv holds at least one environment.
    pub fn is_empty(&self) -> bool {
        self.envs.is_empty()
    }

    /// The environments, e.g. to change their randomisation.
    pub fn envs_mut(&mut self) -> &mut [GraspEnv] {
        &mut self.envs
    }

    /// Resets every environment to its next episode.
    pub fn reset(&mut self) -> Result<Vec<[f32; OBS_DIM]>, EnvError> {
        let mut out = Vec::with_capacity(self.envs.len());
        for (i, env) in self.envs.iter_mut().enumerate() {
            let (obs, _) = env.reset(seed_for(self.base_seed, i, self.episodes[i]))?;
            self.episodes[i] += 1;
            out.push(obs.to_array());
        }
        Ok(out)
    }

    /// Steps every environment with its action, in parallel; ended episodes are reset.
    pub fn step(&mut self, actions: &[Action]) -> Result<VecStep, EnvError> {
        if actions.len() != self.envs.len() {
            return Err(EnvError::ActionLength(actions.len()));
        }
        let chunk = self.envs.len().div_ceil(self.threads);
        let base_seed = self.base_seed;
        type Out = Result<(Observation, f64, bool, bool, Info, Option<Observation>), EnvError>;
        let mut results: Vec<Out> = Vec::with_capacity(self.envs.len());
        std::thread::scope(|scope| {
            let handles: Vec<_> = self
                .envs
                .chunks_mut(chunk)
                .zip(self.episodes.chunks_mut(chunk))
                .zip(actions.chunks(chunk))
                .enumerate()
                .map(|(c, ((envs, episodes), actions))| {
                    scope.spawn(move || {
                        envs.iter_mut()
                            .zip(episodes.iter_mut())
                            .zip(actions)
                            .enumerate()
                            .map(|(j, ((env, episode), action))| -> Out {
                                let step = env.step(action)?;
                                if step.terminated || step.truncated {
                                    let (obs, _) =
                                        env.reset(seed_for(base_seed, c * chunk + j, *episode))?;
                                    *episode += 1;
                                    Ok((
                                        obs,
                                        step.reward,
                                        step.terminated,
                                        step.truncated,
                                        step.info,
                                        Some(step.obs),
                                    ))
                                } else {
                                    Ok((step.obs, step.reward, false, false, step.info, None))
                                }
                            })
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            for h in handles {
                results.extend(h.join().expect("an environment thread panicked"));
            }
        });
        let mut out = VecStep {
            obs: Vec::with_capacity(results.len()),
            rewards: Vec::new(),
            terminated: Vec::new(),
            truncated: Vec::new(),
            infos: Vec::new(),
            final_obs: Vec::new(),
        };
        for r in results {
            let (obs, reward, terminated, truncated, info, final_obs) = r?;
            out.obs.push(obs.to_array());
            out.rewards.push(reward);
            out.terminated.push(terminated);
            out.truncated.push(truncated);
            out.infos.push(info);
            out.final_obs.push(final_obs);
        }
        Ok(out)
    }
}
