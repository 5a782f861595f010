//! N environments stepped in parallel threads, with auto-reset and batched, typed observations.
//!
//! The environments are split into one chunk per thread; the calling thread steps the first
//! chunk and persistent worker threads the others (spawning threads every step costs more than a
//! step here). Environment `i` draws the seed of its `k`-th episode as
//! `base_seed + i · 1 000 000 + k`, so a run is reproducible whatever the number of threads.
//!
//! The batch holds the environments' own [`Observation`]s (f64, `base_link`), not a flattened
//! copy: a policy reads exactly what a single [`TaskEnv`] would have handed it.
//!
//! A step allocates nothing of its own once every buffer has reached its size (after the first
//! reset and step): the actions handed to a worker, a chunk's outcomes and the batch handed back
//! are cleared and refilled in place, and a worker is woken through a mutex and a condition
//! variable rather than a channel (whose queue allocates as messages flow). What the environments
//! allocate inside their own `step`/`reset` is theirs.

use crate::config::{EnvConfig, RandomizationConfig};
use crate::env::obs::Observation;
use crate::env::{Action, EnvError, TaskEnv};
use crate::vec::chunk::{Chunk, VecStep};
use crate::vec::worker::{Job, Worker, spawn_worker};

/// Parallel environments with auto-reset.
pub struct VecEnv {
    local: Chunk,
    workers: Vec<Worker>,
    out: VecStep,
}

/// Which of a mixture's `presets` configurations environment `env` runs: `env % presets`
/// (one rule for the envs, their agents and their teachers).
pub fn preset_of_env(env: usize, presets: usize) -> usize {
    env % presets.max(1)
}

impl VecEnv {
    /// `n` environments of `config`, stepped on `threads` threads (at least 1).
    pub fn new(
        config: &EnvConfig,
        n: usize,
        threads: usize,
        base_seed: u64,
    ) -> Result<Self, EnvError> {
        Self::mixed(std::slice::from_ref(config), n, threads, base_seed)
    }

    /// `n` environments, environment `i` of `configs[`[`preset_of_env`]`]` (a mixture of
    /// presets: e.g. one generalist trained on several families), on `threads` threads.
    pub fn mixed(
        configs: &[EnvConfig],
        n: usize,
        threads: usize,
        base_seed: u64,
    ) -> Result<Self, EnvError> {
        let Some(first) = configs.first() else {
            return Err(EnvError::NoConfigs);
        };
        let config_of = |i: usize| {
            configs
                .get(preset_of_env(i, configs.len()))
                .unwrap_or(first)
        };
        let n = n.max(1);
        let per_thread = n.div_ceil(threads.clamp(1, n));
        let mut chunks = Vec::new();
        let mut first_index = 0;
        while first_index < n {
            let len = per_thread.min(n - first_index);
            let envs = (first_index..first_index + len)
                .map(|i| TaskEnv::new(config_of(i).clone()))
                .collect::<Result<Vec<_>, _>>()?;
            chunks.push(Chunk {
                envs,
                episodes: vec![0; len],
                first_index,
                base_seed,
                actions: Vec::with_capacity(len),
                grip: Vec::with_capacity(len),
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
        self.step_gripping(actions, &[])
    }

    /// [`VecEnv::step`], each env `i` first squeezing with `grip[i]` per finger \[N\] if given
    /// ([`TaskEnv::set_grip_force`]; an empty `grip` changes nothing).
    pub fn step_gripping(
        &mut self,
        actions: &[Action],
        grip: &[Option<f64>],
    ) -> Result<&VecStep, EnvError> {
        let n = self.len();
        if actions.len() != n || !(grip.is_empty() || grip.len() == n) {
            return Err(EnvError::ActionCount {
                expected: n,
                got: if actions.len() != n {
                    actions.len()
                } else {
                    grip.len()
                },
            });
        }
        if self.out.obs.len() != n {
            return Err(EnvError::EpisodeOver);
        }
        let part = |from: usize, len: usize| {
            if grip.is_empty() {
                &[][..]
            } else {
                &grip[from..from + len]
            }
        };
        let mut offset = self.local.envs.len();
        for w in &self.workers {
            let mine = &actions[offset..offset + w.len];
            let squeeze = part(offset, w.len);
            w.start(Job::Step, |chunk| {
                chunk.actions.clear();
                chunk.actions.extend_from_slice(mine);
                chunk.grip.clear();
                chunk.grip.extend_from_slice(squeeze);
            })?;
            offset += w.len;
        }
        let first = self.local.envs.len();
        let local = self.local.step(&actions[..first], part(0, first));
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
            w.quit();
            if let Some(t) = w.thread.take() {
                let _ = t.join();
            }
        }
    }
}
