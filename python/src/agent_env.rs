//! One env as Python steps it (plain Rust, no Python types): the `TaskEnv`, and for a recipe
//! the agent's side ([`EnvAgent`]: the observation becomes the policy input, the policy's output
//! the env action, as in `fairgrasp train`) and the curriculum (its stage sets the scenario
//! randomisation; it advances on the episodes this env plays).

use fairgrasp_env::env::obs::Observation;
use fairgrasp_env::{Action, EnvError, Info, Step, TaskEnv};
use fairgrasp_policy::agent::{AgentConfig, EnvAgent};

use crate::curriculum::EnvCurriculum;
use crate::info::Stage;
use crate::setup::Setup;

/// One env with its agent side and curriculum.
pub(crate) struct AgentEnv {
    env: TaskEnv,
    agent: Option<(AgentConfig, EnvAgent)>,
    curriculum: EnvCurriculum,
    /// The observation handed out last: the policy input (the env's flat observation without
    /// an agent).
    input: Vec<f32>,
    /// The env's own observation the next action acts on.
    last: Option<Observation>,
}

impl AgentEnv {
    pub fn new(setup: &Setup) -> Result<Self, EnvError> {
        let mut env = TaskEnv::new(setup.config.clone())?;
        let curriculum = EnvCurriculum::new(setup);
        if let Some(r) = curriculum.randomization() {
            env.set_randomization(r)?;
        }
        Ok(Self {
            agent: setup
                .agent
                .clone()
                .map(|a| (a.clone(), EnvAgent::new(&a, &setup.config))),
            input: vec![0.0; setup.obs_dim()],
            curriculum,
            env,
            last: None,
        })
    }

    pub fn env(&self) -> &TaskEnv {
        &self.env
    }

    /// The observation handed out last.
    pub fn input(&self) -> &[f32] {
        &self.input
    }

    /// The env's own observation the next action acts on (None before the first reset).
    pub fn last(&self) -> Option<&Observation> {
        self.last.as_ref()
    }

    pub fn stage(&self) -> Option<Stage> {
        self.curriculum.stage()
    }

    /// Moves the curriculum to `stage` (clamped to the last) with empty windows; the new
    /// randomisation holds from the next reset.
    pub fn set_stage(&mut self, stage: usize) -> Result<(), EnvError> {
        self.curriculum
            .move_to(stage, |r| self.env.set_randomization(r))
    }

    fn observe(&mut self, obs: &Observation) {
        match &mut self.agent {
            Some((config, agent)) => agent.observe(config, obs, &mut self.input),
            None => self.input.copy_from_slice(&obs.to_array()),
        }
        self.last = Some(*obs);
    }

    /// Starts the episode of scenario `seed` (drawn under the curriculum's stage).
    pub fn reset(&mut self, seed: u64) -> Result<Info, EnvError> {
        let (obs, info) = self.env.reset(seed)?;
        if let Some((_, agent)) = &mut self.agent {
            agent.reset(seed);
        }
        self.observe(&obs);
        Ok(info)
    }

    /// One step with the policy's output `action` (the env action itself without an agent);
    /// returns the env action taken and the step, whose record carries the agent's verdict.
    pub fn step(&mut self, action: &[f64; 7]) -> Result<(Action, Step), EnvError> {
        let obs = self.last.ok_or(EnvError::EpisodeOver)?;
        let env_action = match &mut self.agent {
            Some((config, agent)) => {
                let policy = action.map(|v| v as f32);
                agent.act(config, &obs, &policy, None)
            }
            None => Action(*action),
        };
        if let Some(force) = self.agent.as_ref().and_then(|(_, a)| a.grip_force()) {
            self.env.set_grip_force(force)?;
        }
        let mut step = self.env.step(&env_action)?;
        if step.terminated || step.truncated {
            let agent = self.agent.as_ref().map(|(_, a)| a);
            if let Some(r) = self.curriculum.episode_ended(&mut step.info, agent) {
                self.env.set_randomization(r)?;
            }
        }
        self.observe(&step.obs);
        Ok((env_action, step))
    }
}
