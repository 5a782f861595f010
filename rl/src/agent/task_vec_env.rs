//! Every task's environment as PPO sees it: vectorised, each env stepped through its
//! [`EnvAgent`] (the script in residual mode): the baseline's action appended to each
//! observation and the policy's output composed with it, or the task script's features appended
//! and the policy's output correcting it. Python's recipe envs step through the same
//! [`EnvAgent`].
//!
//! The script acts on the environments' own typed [`Observation`](fairgrasp_env::Observation)s
//! (f64, `base_link`), at every step and at episode ends, exactly as in evaluation; the policy
//! input is built from the same observation by [`AgentConfig::write_input`]. Every buffer is sized
//! in `new` and refilled in place: a step allocates nothing here.

use fairgrasp_env::vec::{VecEnv, preset_of_env};
use fairgrasp_env::{Action, EnvConfig, EnvError};

use crate::agent::grasp_agent::{ACT_DIM, AgentConfig};
use crate::ppo::vec_api::{EpisodeStats, StepBatch, VecEnvError, VecEnvironment, check_finite};
use fairgrasp_env::robot::tcp_action::TaskSpaceAction;
use fairgrasp_policy::agent::EnvAgent;

/// Vectorised grasp envs plus one agent side (script) per env.
pub struct TaskVecEnv {
    inner: VecEnv,
    agent: AgentConfig,
    /// Task-space to joint actions (`agent.action_space = "tcp"`).
    task_space: Option<TaskSpaceAction>,
    agents: Vec<EnvAgent>,
    /// The composed actions handed to the envs.
    env_actions: Vec<Action>,
    /// The squeeze each env's script asks for (empty unless `agent.squeeze`).
    grip: Vec<Option<f64>>,
    returns: Vec<f32>,
    lengths: Vec<usize>,
    batch: StepBatch,
}

impl TaskVecEnv {
    /// `n` envs on `threads` threads; episode seeds start at `seed`.
    pub fn new(
        config: &EnvConfig,
        agent: AgentConfig,
        n: usize,
        threads: usize,
        seed: u64,
    ) -> Result<Self, EnvError> {
        Self::mixed(std::slice::from_ref(config), agent, n, threads, seed)
    }

    /// `n` envs, env `i` of `configs[preset_of_env(i, configs.len())]` ([`VecEnv::mixed`]),
    /// each with its own script of its config.
    pub fn mixed(
        configs: &[EnvConfig],
        agent: AgentConfig,
        n: usize,
        threads: usize,
        seed: u64,
    ) -> Result<Self, EnvError> {
        let inner = VecEnv::mixed(configs, n, threads, seed)?;
        let n = inner.len();
        let config = &configs[0];
        Ok(Self {
            inner,
            agents: (0..n)
                .map(|i| EnvAgent::new(&agent, &configs[preset_of_env(i, configs.len())]))
                .collect(),
            env_actions: vec![Action::hold_open(); n],
            grip: if agent.squeeze {
                vec![None; n]
            } else {
                Vec::new()
            },
            returns: vec![0.0; n],
            lengths: vec![0; n],
            batch: StepBatch::new(n, agent.input_dim()),
            task_space: agent.task_space(config),
            agent,
        })
    }

    /// The vectorised env (e.g. to change the randomisation).
    pub fn inner_mut(&mut self) -> &mut VecEnv {
        &mut self.inner
    }

    /// The joint baseline's action for env `e`'s current observation (None in pure mode and
    /// for a task-space residual): what the next step composes the policy's output with.
    pub fn baseline_action(&self, e: usize) -> Option<Action> {
        self.agents.get(e).and_then(|a| a.base_action().copied())
    }

    fn row(&self, e: usize) -> std::ops::Range<usize> {
        let dim = self.agent.input_dim();
        e * dim..(e + 1) * dim
    }
}

impl VecEnvironment for TaskVecEnv {
    fn n_envs(&self) -> usize {
        self.agents.len()
    }
    fn obs_dim(&self) -> usize {
        self.agent.input_dim()
    }
    fn act_dim(&self) -> usize {
        ACT_DIM
    }

    fn reset(&mut self) -> Result<&[f32], VecEnvError> {
        self.inner.reset()?;
        let now = self.inner.batch();
        for e in 0..self.agents.len() {
            let row = self.row(e);
            self.agents[e].reset(now.seeds[e]);
            self.agents[e].observe(&self.agent, &now.obs[e], &mut self.batch.obs[row]);
        }
        self.returns.fill(0.0);
        self.lengths.fill(0);
        self.batch.rewards.fill(0.0);
        self.batch.terminated.fill(false);
        self.batch.truncated.fill(false);
        self.batch.finished.fill(None);
        Ok(&self.batch.obs)
    }

    fn step(&mut self, actions: &[f32]) -> Result<&StepBatch, VecEnvError> {
        let n = self.agents.len();
        if actions.len() != n * ACT_DIM {
            return Err(VecEnvError::ActionShape {
                n_envs: n,
                act_dim: ACT_DIM,
                got: actions.len(),
            });
        }
        check_finite(actions, ACT_DIM, "action")?;
        let now = &self.inner.batch().obs;
        for (((slot, policy), obs), agent) in self
            .env_actions
            .iter_mut()
            .zip(actions.chunks(ACT_DIM))
            .zip(now)
            .zip(&mut self.agents)
        {
            *slot = agent.act(&self.agent, obs, policy, self.task_space.as_ref());
        }
        for (force, agent) in self.grip.iter_mut().zip(&self.agents) {
            *force = agent.grip_force();
        }
        let step = self.inner.step_gripping(&self.env_actions, &self.grip)?;
        for e in 0..n {
            let row = e * self.agent.input_dim()..(e + 1) * self.agent.input_dim();
            let reward = step.rewards[e] as f32;
            self.returns[e] += reward;
            self.lengths[e] += 1;
            self.batch.rewards[e] = reward;
            self.batch.terminated[e] = step.terminated[e];
            self.batch.truncated[e] = step.truncated[e];
            self.batch.finished[e] = None;
            if step.terminated[e] || step.truncated[e] {
                // The final observation with the script's part the policy would have seen.
                if let Some(last) = &step.final_obs[e] {
                    self.agents[e].observe(
                        &self.agent,
                        last,
                        &mut self.batch.final_obs[row.clone()],
                    );
                }
                // The env's record of the episode, with the script's verdict as in evaluation.
                let verdict = self.agents[e].verdict();
                let outcome = step.infos[e]
                    .episode
                    .clone()
                    .map(|r| r.with_policy_verdict(verdict).outcome);
                self.batch.finished[e] = Some(EpisodeStats {
                    success: outcome == Some(fairgrasp_types::Outcome::Success),
                    outcome,
                    episode_return: self.returns[e],
                    length: self.lengths[e],
                    object_xy: step.infos[e].scenario.map(|s| s.object_xy),
                });
                self.returns[e] = 0.0;
                self.lengths[e] = 0;
                self.agents[e].reset(step.seeds[e]);
            }
            self.agents[e].observe(&self.agent, &step.obs[e], &mut self.batch.obs[row]);
        }
        Ok(&self.batch)
    }
}
