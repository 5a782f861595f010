//! N envs as Python steps them (plain Rust, no Python types): the Rust `VecEnv` (its envs
//! stepped in parallel on its threads, auto-reset in the step that ends an episode), each env's
//! agent side for a recipe ([`EnvAgent`], as `fairgrasp train` steps it) and one curriculum
//! shared by all envs (as the trainer shares it: every ended episode counts, in env order, and
//! a new stage's randomisation holds from each env's next reset).

use fairgrasp_env::vec::{VecEnv, VecStep};
use fairgrasp_env::{Action, EnvError, Info};
use fairgrasp_policy::agent::{AgentConfig, EnvAgent};

use crate::curriculum::EnvCurriculum;
use crate::info::Stage;
use crate::setup::Setup;

/// The vectorised envs, their agents and the shared curriculum.
pub(crate) struct AgentVecEnv {
    inner: VecEnv,
    agent: Option<(AgentConfig, Vec<EnvAgent>)>,
    curriculum: EnvCurriculum,
    n: usize,
    dim: usize,
    /// Observations handed out, `[env][dim]`: policy inputs (after an auto-reset, the new
    /// episode's first).
    obs: Vec<f32>,
    /// For each env whose episode ended in the last step: its last observation (as a policy
    /// input, `dim` values) and its last info (the record with the agent's verdict).
    ended: Vec<(usize, Vec<f32>, Info)>,
    actions: Vec<Action>,
}

impl AgentVecEnv {
    /// `n` envs on `threads` threads; env `i`'s `k`-th episode plays scenario seed
    /// `seed + i · 1 000 000 + k`.
    pub fn new(setup: &Setup, n: usize, threads: usize, seed: u64) -> Result<Self, EnvError> {
        let mut inner = VecEnv::new(&setup.config, n, threads, seed)?;
        let curriculum = EnvCurriculum::new(setup);
        if let Some(r) = curriculum.randomization() {
            inner.set_randomization(&r)?;
        }
        let dim = setup.obs_dim();
        Ok(Self {
            agent: setup.agent.clone().map(|a| {
                let agents = (0..n).map(|_| EnvAgent::new(&a, &setup.config)).collect();
                (a, agents)
            }),
            curriculum,
            n,
            dim,
            obs: vec![0.0; n * dim],
            ended: Vec::new(),
            actions: vec![Action::hold_open(); n],
            inner,
        })
    }

    pub fn len(&self) -> usize {
        self.n
    }

    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The observations handed out last, `[env][dim]`.
    pub fn obs(&self) -> &[f32] {
        &self.obs
    }

    /// The envs whose episode ended in the last step: index, last observation, last info.
    pub fn ended(&self) -> &[(usize, Vec<f32>, Info)] {
        &self.ended
    }

    /// The last reset's or step's batch (rewards, flags, infos, the episodes' seeds now).
    pub fn batch(&self) -> &VecStep {
        self.inner.batch()
    }

    pub fn stage(&self) -> Option<Stage> {
        self.curriculum.stage()
    }

    /// Moves the shared curriculum to `stage` (clamped to the last) with empty windows.
    pub fn set_stage(&mut self, stage: usize) -> Result<(), EnvError> {
        self.curriculum
            .move_to(stage, |r| self.inner.set_randomization(&r))
    }

    fn write_obs(
        agent: &mut Option<(AgentConfig, Vec<EnvAgent>)>,
        e: usize,
        obs: &fairgrasp_env::Observation,
        out: &mut [f32],
    ) {
        match agent {
            Some((config, agents)) => agents[e].observe(config, obs, out),
            None => out.copy_from_slice(&obs.to_array()),
        }
    }

    /// Starts every env's next episode.
    pub fn reset(&mut self) -> Result<(), EnvError> {
        self.inner.reset()?;
        self.ended.clear();
        let batch = self.inner.batch();
        for e in 0..self.n {
            if let Some((_, agents)) = &mut self.agent {
                agents[e].reset(batch.seeds[e]);
            }
            let row = e * self.dim..(e + 1) * self.dim;
            Self::write_obs(&mut self.agent, e, &batch.obs[e], &mut self.obs[row]);
        }
        Ok(())
    }

    /// Steps every env with its row of `actions` (`[env][7]`: the policy's outputs, or the env
    /// actions themselves without an agent); the envs step in parallel.
    pub fn step(&mut self, actions: &[[f64; 7]]) -> Result<(), EnvError> {
        if actions.len() != self.n {
            return Err(EnvError::ActionCount {
                expected: self.n,
                got: actions.len(),
            });
        }
        let now = &self.inner.batch().obs;
        if now.len() != self.n {
            return Err(EnvError::EpisodeOver);
        }
        for (e, (slot, a)) in self.actions.iter_mut().zip(actions).enumerate() {
            *slot = match &mut self.agent {
                Some((config, agents)) => {
                    let policy = a.map(|v| v as f32);
                    agents[e].act(config, &now[e], &policy, None)
                }
                None => Action(*a),
            };
        }
        let grip: Vec<Option<f64>> = match &self.agent {
            Some((config, agents)) if config.squeeze => {
                agents.iter().map(|a| a.grip_force()).collect()
            }
            _ => Vec::new(),
        };
        self.inner.step_gripping(&self.actions, &grip)?;
        self.ended.clear();
        let mut advanced = None;
        let batch = self.inner.batch();
        for e in 0..self.n {
            if batch.terminated[e] || batch.truncated[e] {
                let mut last = vec![0.0; self.dim];
                if let Some(final_obs) = &batch.final_obs[e] {
                    Self::write_obs(&mut self.agent, e, final_obs, &mut last);
                }
                let mut info = batch.infos[e].clone();
                let agent = self.agent.as_ref().map(|(_, a)| &a[e]);
                if let Some(r) = self.curriculum.episode_ended(&mut info, agent) {
                    advanced = Some(r);
                }
                self.ended.push((e, last, info));
                if let Some((_, agents)) = &mut self.agent {
                    agents[e].reset(batch.seeds[e]);
                }
            }
            let row = e * self.dim..(e + 1) * self.dim;
            Self::write_obs(&mut self.agent, e, &batch.obs[e], &mut self.obs[row]);
        }
        if let Some(r) = advanced {
            self.inner.set_randomization(&r)?;
        }
        Ok(())
    }
}
