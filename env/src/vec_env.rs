//! N environments stepped in parallel threads, with auto-reset and batched, typed observations.
//!
//! The environments are split into one chunk per thread; the calling thread steps the first
//! chunk and persistent worker threads the others (spawning threads every step costs more than a
//! step here). Environment `i` draws the seed of its `k`-th episode as
//! `base_seed + i · 1 000 000 + k`, so a run is reproducible whatever the number of threads.
//!
//! The batch holds the environments' own [`Observation`]s (f64, `base_link`), not a flattened
//! copy: a policy reads exactly what a single [`GraspEnv`] would have handed it.
//!
//! A step allocates nothing of its own once every buffer has reached its size (after the first
//! reset and step): the actions handed to a worker, a chunk's outcomes and the batch handed back
//! are cleared and refilled in place, and a worker is woken through a mutex and a condition
//! variable rather than a channel (whose queue allocates as messages flow). What the environments
//! allocate inside their own `step`/`reset` is theirs.

use crate::config::{EnvConfig, RandomizationConfig};
use crate::env::{Action, EnvError, GraspEnv, Info};
use crate::obs::Observation;
use crate::vec_worker::{Job, Worker, spawn_worker};

/// One batched step (or reset), one entry per environment in index order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VecStep {
    /// Observation to act on next: after an auto-reset, the new episode's first one.
    pub obs: Vec<Observation>,
    /// Reward of this step (0 after a reset).
    pub rewards: Vec<f64>,
    /// The episode ended in a terminal state (success or failure) in this step.
    pub terminated: Vec<bool>,
    /// The episode was cut (time limit, physics fault) in this step.
    pub truncated: Vec<bool>,
    /// What else happened (after a reset: the reset's info).
    pub infos: Vec<Info>,
    /// The last observation of an episode that ended in this step (for bootstrapping).
    pub final_obs: Vec<Option<Observation>>,
    /// Seed of the episode each environment is in now (after an auto-reset, the new one's).
    pub seeds: Vec<u64>,
}

impl VecStep {
    fn clear(&mut self) {
        self.obs.clear();
        self.rewards.clear();
        self.terminated.clear();
        self.truncated.clear();
        self.infos.clear();
        self.final_obs.clear();
        self.seeds.clear();
    }

    fn push(&mut self, obs: Observation, reward: f64, flags: [bool; 2], info: Info, seed: u64) {
        self.push_with_final(obs, reward, flags, info, None, seed);
    }

    fn push_with_final(
        &mut self,
        obs: Observation,
        reward: f64,
        [terminated, truncated]: [bool; 2],
        info: Info,
        final_obs: Option<Observation>,
        seed: u64,
    ) {
        self.obs.push(obs);
        self.rewards.push(reward);
        self.terminated.push(terminated);
        self.truncated.push(truncated);
        self.infos.push(info);
        self.final_obs.push(final_obs);
        self.seeds.push(seed);
    }

    /// Moves `other`'s entries to the end of this batch (keeps both allocations).
    fn append_from(&mut self, other: &mut VecStep) {
        self.obs.extend_from_slice(&other.obs);
        self.rewards.extend_from_slice(&other.rewards);
        self.terminated.extend_from_slice(&other.terminated);
        self.truncated.extend_from_slice(&other.truncated);
        self.infos.append(&mut other.infos);
        self.final_obs.extend_from_slice(&other.final_obs);
        self.seeds.extend_from_slice(&other.seeds);
    }
}

fn seed_for(base: u64, env: usize, episode: u64) -> u64 {
    base.wrapping_add(env as u64 * 1_000_000)
        .wrapping_add(episode)
}

/// The environments one thread owns, and their outcomes.
pub(crate) struct Chunk {
    pub(crate) envs: Vec<GraspEnv>,
    /// Episodes started so far, per environment.
    episodes: Vec<u64>,
    first_index: usize,
    base_seed: u64,
    /// A worker's actions, copied in by the calling thread.
    actions: Vec<Action>,
    out: VecStep,
}

impl Chunk {
    /// Seed of environment `j`'s next episode; counts it as started.
    fn next_seed(&mut self, j: usize) -> u64 {
        let seed = seed_for(self.base_seed, self.first_index + j, self.episodes[j]);
        self.episodes[j] += 1;
        seed
    }

    pub(crate) fn reset(&mut self) -> Result<(), EnvError> {
        self.out.clear();
        for j in 0..self.envs.len() {
            let seed = self.next_seed(j);
            let (obs, info) = self.envs[j].reset(seed)?;
            self.out.push(obs, 0.0, [false, false], info, seed);
        }
        Ok(())
    }

    fn step(&mut self, actions: &[Action]) -> Result<(), EnvError> {
        self.out.clear();
        for (j, action) in actions.iter().enumerate().take(self.envs.len()) {
            let step = self.envs[j].step(action)?;
            let flags = [step.terminated, step.truncated];
            if step.terminated || step.truncated {
                let seed = self.next_seed(j);
                let (obs, _) = self.envs[j].reset(seed)?;
                self.out
                    .push_with_final(obs, step.reward, flags, step.info, Some(step.obs), seed);
            } else {
                let seed = seed_for(
                    self.base_seed,
                    self.first_index + j,
                    self.episodes[j].saturating_sub(1),
                );
                self.out.push(step.obs, step.reward, flags, step.info, seed);
            }
        }
        Ok(())
    }

    /// Steps with the actions a worker was handed.
    pub(crate) fn step_own_actions(&mut self) -> Result<(), EnvError> {
        let actions = std::mem::take(&mut self.actions);
        let result = self.step(&actions);
        self.actions = actions;
        result
    }

    pub(crate) fn set_randomization(&mut self, r: &RandomizationConfig) -> Result<(), EnvError> {
        self.envs
            .iter_mut()
            .try_for_each(|e| e.set_randomization(r.clone()))
    }
}

/// Parallel environments with auto-reset.
pub struct VecEnv {
    local: Chunk,
    workers: Vec<Worker>,
    out: VecStep,
}

impl VecEnv {
    /// `n` environments of `config`, stepped on `threads` threads (at least 1).
    pub fn new(
        config: &EnvConfig,
        n: usize,
        threads: usize,
        base_seed: u64,
    ) -> Result<Self, EnvError> {
        let n = n.max(1);
        let per_thread = n.div_ceil(threads.clamp(1, n));
        let mut chunks = Vec::new();
        let mut first_index = 0;
        while first_index < n {
            let len = per_thread.min(n - first_index);
            let envs = (0..len)
                .map(|_| GraspEnv::new(config.clone()))
                .collect::<Result<Vec<_>, _>>()?;
            chunks.push(Chunk {
                envs,
                episodes: vec![0; len],
                first_index,
                base_seed,
                actions: Vec::with_capacity(len),
                out: VecStep::default(),
            });
            first_index += len;
        }
        let local = chunks.remove(0);
        let workers = chunks.into_iter().map(spawn_worker).collect();
        Ok(Self {
            local,
            workers,
            out: VecStep::default(),
        })
    }

    /// Number of environments.
    pub fn len(&self) -> usize {
        self.local.envs.len() + self.workers.iter().map(|w| w.len).sum::<usize>()
    }

    /// Always false: a VecEnv holds at least one environment.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The batch of the last reset or step (after a reset: first observations, zero rewards,
    /// the new episodes' seeds; empty before the first reset or after an error).
    pub fn batch(&self) -> &VecStep {
        &self.out
    }

    /// Resets every environment to its next episode; returns their first observations.
    pub fn reset(&mut self) -> Result<&[Observation], EnvError> {
        for w in &self.workers {
            w.start(Job::Reset, |_| {})?;
        }
        let local = self.local.reset();
        self.gather(local)?;
        Ok(&self.out.obs)
    }

    /// Replaces every environment's randomisation (takes effect at their next reset).
    pub fn set_randomization(&mut self, r: &RandomizationConfig) -> Result<(), EnvError> {
        for w in &self.workers {
            w.start(Job::SetRandomization(r.clone()), |_| {})?;
        }
        let mut first_error = self.local.set_randomization(r).err();
        for w in &self.workers {
            if let Err(e) = w.finish()?.1 {
                first_error.get_or_insert(e);
            }
        }
        first_error.map_or(Ok(()), Err)
    }

    /// Steps every environment with its action, in parallel; ended episodes are reset.
    pub fn step(&mut self, actions: &[Action]) -> Result<&VecStep, EnvError> {
        let n = self.len();
        if actions.len() != n {
            return Err(EnvError::ActionCount {
                expected: n,
                got: actions.len(),
            });
        }
        if self.out.obs.len() != n {
            return Err(EnvError::EpisodeOver);
        }
        let mut offset = self.local.envs.len();
        for w in &self.workers {
            let mine = &actions[offset..offset + w.len];
            w.start(Job::Step, |chunk| {
                chunk.actions.clear();
                chunk.actions.extend_from_slice(mine);
            })?;
            offset += w.len;
        }
        let local = self.local.step(&actions[..self.local.envs.len()]);
        self.gather(local)?;
        Ok(&self.out)
    }

    /// Collects every chunk's outcomes in index order; the first error wins, but every worker
    /// is waited for so that none is left busy.
    fn gather(&mut self, local: Result<(), EnvError>) -> Result<(), EnvError> {
        self.out.clear();
        let mut first_error = local.err();
        self.out.append_from(&mut self.local.out);
        for w in &self.workers {
            let (mut shared, result) = w.finish()?;
            match result {
                Ok(()) => self.out.append_from(&mut shared.chunk.out),
                Err(e) => {
                    first_error.get_or_insert(e);
                }
            }
        }
        match first_error {
            Some(e) => {
                // A half-filled batch must not be stepped from.
                self.out.clear();
                Err(e)
            }
            None => Ok(()),
        }
    }
}

impl Drop for VecEnv {
    fn drop(&mut self) {
        for w in &mut self.workers {
            if let Ok(mut shared) = w.mailbox.0.lock() {
                shared.job = Job::Quit;
                w.mailbox.1.notify_all();
            }
            if let Some(t) = w.thread.take() {
                let _ = t.join();
            }
        }
    }
}
