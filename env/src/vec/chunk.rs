//! What one thread of [`crate::vec::VecEnv`] owns: a chunk of environments stepped in order
//! with auto-reset, and the batch of their outcomes ([`VecStep`]).

use crate::config::RandomizationConfig;
use crate::env::obs::Observation;
use crate::env::{Action, EnvError, Info, TaskEnv};

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
    pub(crate) fn clear(&mut self) {
        self.obs.clear();
        self.rewards.clear();
        self.terminated.clear();
        self.truncated.clear();
        self.infos.clear();
        self.final_obs.clear();
        self.seeds.clear();
    }

    pub(crate) fn push(
        &mut self,
        obs: Observation,
        reward: f64,
        flags: [bool; 2],
        info: Info,
        seed: u64,
    ) {
        self.push_with_final(obs, reward, flags, info, None, seed);
    }

    pub(crate) fn push_with_final(
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
    pub(crate) fn append_from(&mut self, other: &mut VecStep) {
        self.obs.extend_from_slice(&other.obs);
        self.rewards.extend_from_slice(&other.rewards);
        self.terminated.extend_from_slice(&other.terminated);
        self.truncated.extend_from_slice(&other.truncated);
        self.infos.append(&mut other.infos);
        self.final_obs.extend_from_slice(&other.final_obs);
        self.seeds.extend_from_slice(&other.seeds);
    }
}

pub(crate) fn seed_for(base: u64, env: usize, episode: u64) -> u64 {
    base.wrapping_add(env as u64 * 1_000_000)
        .wrapping_add(episode)
}

/// The environments one thread owns, and their outcomes.
pub(crate) struct Chunk {
    pub(crate) envs: Vec<TaskEnv>,
    /// Episodes started so far, per environment.
    pub(crate) episodes: Vec<u64>,
    pub(crate) first_index: usize,
    pub(crate) base_seed: u64,
    /// A worker's actions, copied in by the calling thread.
    pub(crate) actions: Vec<Action>,
    /// Each env's squeeze per finger \[N\] for this step, if asked (copied in with the actions).
    pub(crate) grip: Vec<Option<f64>>,
    pub(crate) out: VecStep,
}

impl Chunk {
    /// Seed of environment `j`'s next episode; counts it as started.
    pub(crate) fn next_seed(&mut self, j: usize) -> u64 {
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

    /// Steps env `j` with `actions[j]`, squeezing with `grip[j]` \[N\] first if given.
    pub(crate) fn step(
        &mut self,
        actions: &[Action],
        grip: &[Option<f64>],
    ) -> Result<(), EnvError> {
        self.out.clear();
        for (j, action) in actions.iter().enumerate().take(self.envs.len()) {
            if let Some(&Some(force)) = grip.get(j) {
                self.envs[j].set_grip_force(force)?;
            }
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
        let grip = std::mem::take(&mut self.grip);
        let result = self.step(&actions, &grip);
        self.actions = actions;
        self.grip = grip;
        result
    }

    pub(crate) fn set_randomization(&mut self, r: &RandomizationConfig) -> Result<(), EnvError> {
        self.envs
            .iter_mut()
            .try_for_each(|e| e.set_randomization(r.clone()))
    }
}
