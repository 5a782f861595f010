//! N environments stepped in parallel threads, with auto-reset and batched observations.
//!
//! The environments are split into one chunk per thread; the calling thread steps the first
//! chunk and persistent worker threads the others (spawning threads every step costs more than a
//! step here). Environment `i` draws the seed of its `k`-th episode as
//! `base_seed + i · 1 000 000 + k`, so a run is reproducible whatever the number of threads.

use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;

use crate::config::{EnvConfig, RandomizationConfig};
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

/// One environment's step outcome: (next obs, reward, terminated, truncated, info, final obs).
type Outcome = (Observation, f64, bool, bool, Info, Option<Observation>);

fn seed_for(base: u64, env: usize, episode: u64) -> u64 {
    base.wrapping_add(env as u64 * 1_000_000)
        .wrapping_add(episode)
}

/// The environments one thread owns.
struct Chunk {
    envs: Vec<GraspEnv>,
    episodes: Vec<u64>,
    first_index: usize,
    base_seed: u64,
}

impl Chunk {
    fn reset(&mut self) -> Result<Vec<Observation>, EnvError> {
        let mut out = Vec::with_capacity(self.envs.len());
        for (j, env) in self.envs.iter_mut().enumerate() {
            let (obs, _) = env.reset(seed_for(
                self.base_seed,
                self.first_index + j,
                self.episodes[j],
            ))?;
            self.episodes[j] += 1;
            out.push(obs);
        }
        Ok(out)
    }

    fn step(&mut self, actions: &[Action]) -> Result<Vec<Outcome>, EnvError> {
        let mut out = Vec::with_capacity(self.envs.len());
        for (j, (env, action)) in self.envs.iter_mut().zip(actions).enumerate() {
            let step = env.step(action)?;
            if step.terminated || step.truncated {
                let seed = seed_for(self.base_seed, self.first_index + j, self.episodes[j]);
                let (obs, _) = env.reset(seed)?;
                self.episodes[j] += 1;
                out.push((
                    obs,
                    step.reward,
                    step.terminated,
                    step.truncated,
                    step.info,
                    Some(step.obs),
                ));
            } else {
                out.push((step.obs, step.reward, false, false, step.info, None));
            }
        }
        Ok(out)
    }

    fn set_randomization(&mut self, r: &RandomizationConfig) -> Result<(), EnvError> {
        self.envs
            .iter_mut()
            .try_for_each(|e| e.set_randomization(r.clone()))
    }
}

enum Command {
    Reset,
    Step(Vec<Action>),
    SetRandomization(RandomizationConfig),
}

enum Reply {
    Reset(Result<Vec<Observation>, EnvError>),
    Step(Result<Vec<Outcome>, EnvError>),
    Done(Result<(), EnvError>),
}

struct Worker {
    commands: Sender<Command>,
    replies: Receiver<Reply>,
    thread: Option<JoinHandle<()>>,
    len: usize,
}

fn spawn_worker(mut chunk: Chunk) -> Worker {
    let (commands, inbox) = channel::<Command>();
    let (outbox, replies) = channel::<Reply>();
    let len = chunk.envs.len();
    let thread = std::thread::spawn(move || {
        while let Ok(command) = inbox.recv() {
            let reply = match command {
                Command::Reset => Reply::Reset(chunk.reset()),
                Command::Step(actions) => Reply::Step(chunk.step(&actions)),
                Command::SetRandomization(r) => Reply::Done(chunk.set_randomization(&r)),
            };
            if outbox.send(reply).is_err() {
                break;
            }
        }
    });
    Worker {
        commands,
        replies,
        thread: Some(thread),
        len,
    }
}

/// Parallel environments with auto-reset.
pub struct VecEnv {
    local: Chunk,
    workers: Vec<Worker>,
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
            });
            first_index += len;
        }
        let local = chunks.remove(0);
        let workers = chunks.into_iter().map(spawn_worker).collect();
        Ok(Self { local, workers })
    }

    /// Number of environments.
    pub fn len(&self) -> usize {
        self.local.envs.len() + self.workers.iter().map(|w| w.len).sum::<usize>()
    }

    /// Always false: a VecEnv holds at least one environment.
    pub fn is_empty(&self) -> bool {
        false
    }

    fn worker_gone() -> EnvError {
        EnvError::WorkerLost
    }

    /// Resets every environment to its next episode.
    pub fn reset(&mut self) -> Result<Vec<[f32; OBS_DIM]>, EnvError> {
        for w in &self.workers {
            w.commands
                .send(Command::Reset)
                .map_err(|_| Self::worker_gone())?;
        }
        let mut out: Vec<[f32; OBS_DIM]> = self
            .local
            .reset()?
            .iter()
            .map(Observation::to_array)
            .collect();
        for w in &self.workers {
            match w.replies.recv().map_err(|_| Self::worker_gone())? {
                Reply::Reset(r) => out.extend(r?.iter().map(Observation::to_array)),
                _ => return Err(Self::worker_gone()),
            }
        }
        Ok(out)
    }

    /// Replaces every environment's randomisation (takes effect at their next reset).
    pub fn set_randomization(&mut self, r: &RandomizationConfig) -> Result<(), EnvError> {
        for w in &self.workers {
            w.commands
                .send(Command::SetRandomization(r.clone()))
                .map_err(|_| Self::worker_gone())?;
        }
        self.local.set_randomization(r)?;
        for w in &self.workers {
            match w.replies.recv().map_err(|_| Self::worker_gone())? {
                Reply::Done(r) => r?,
                _ => return Err(Self::worker_gone()),
            }
        }
        Ok(())
    }

    /// Steps every environment with its action, in parallel; ended episodes are reset.
    pub fn step(&mut self, actions: &[Action]) -> Result<VecStep, EnvError> {
        if actions.len() != self.len() {
            return Err(EnvError::ActionCount {
                expected: self.len(),
                got: actions.len(),
            });
        }
        let mut offset = self.local.envs.len();
        for w in &self.workers {
            let batch = actions[offset..offset + w.len].to_vec();
            w.commands
                .send(Command::Step(batch))
                .map_err(|_| Self::worker_gone())?;
            offset += w.len;
        }
        let mut outcomes = self.local.step(&actions[..self.local.envs.len()])?;
        for w in &self.workers {
            match w.replies.recv().map_err(|_| Self::worker_gone())? {
                Reply::Step(r) => outcomes.extend(r?),
                _ => return Err(Self::worker_gone()),
            }
        }
        let n = outcomes.len();
        let mut out = VecStep {
            obs: Vec::with_capacity(n),
            rewards: Vec::with_capacity(n),
            terminated: Vec::with_capacity(n),
            truncated: Vec::with_capacity(n),
            infos: Vec::with_capacity(n),
            final_obs: Vec::with_capacity(n),
        };
        for (obs, reward, terminated, truncated, info, final_obs) in outcomes {
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

impl Drop for VecEnv {
    fn drop(&mut self) {
        for w in &mut self.workers {
            // Closing the command channel ends the worker's loop.
            let (dead, _) = channel();
            drop(std::mem::replace(&mut w.commands, dead));
            if let Some(t) = w.thread.take() {
                let _ = t.join();
            }
        }
    }
}
