//! The grasping environment as PPO sees it: vectorised, with the baseline's action appended to
//! each observation and the policy's output composed with it (residual mode).

use fairgrasp_env::policy::Policy;
use fairgrasp_env::vec_env::VecEnv;
use fairgrasp_env::{Action, EnvConfig, EnvError, Observation};
use fairgrasp_planner::ScriptedGrasp;

use crate::agent::{ACT_DIM, AgentConfig, OBS_DIM};
use crate::vec_api::{EpisodeStats, StepBatch, VecEnvironment};

/// Vectorised grasp envs plus one baseline per env.
pub struct GraspVecEnv {
    inner: VecEnv,
    agent: AgentConfig,
    baselines: Vec<Option<ScriptedGrasp>>,
    base_actions: Vec<Option<Action>>,
    raw_obs: Vec<[f32; OBS_DIM]>,
    returns: Vec<f32>,
    lengths: Vec<usize>,
    episode: u64,
}

impl GraspVecEnv {
    /// `n` envs on `threads` threads; episode seeds start at `seed`.
    pub fn new(
        config: &EnvConfig,
        agent: AgentConfig,
        n: usize,
        threads: usize,
        seed: u64,
    ) -> Result<Self, EnvError> {
        Ok(Self {
            inner: VecEnv::new(config, n, threads, seed)?,
            baselines: (0..n).map(|_| agent.baseline(config)).collect(),
            base_actions: vec![None; n],
            raw_obs: Vec::new(),
            returns: vec![0.0; n],
            lengths: vec![0; n],
            agent,
            episode: 0,
        })
    }

    /// The vectorised env (e.g. to change the randomisation).
    pub fn inner_mut(&mut self) -> &mut VecEnv {
        &mut self.inner
    }

    /// Runs the baselines on the current observations and builds the policy inputs.
    fn inputs(&mut self) -> Vec<Vec<f32>> {
        let mut out = Vec::with_capacity(self.raw_obs.len());
        for (e, obs) in self.raw_obs.iter().enumerate() {
            let base = self.baselines[e]
                .as_mut()
                .map(|b| b.act(&Observation::from_array(obs)));
            out.push(self.agent.input(obs, base.as_ref()));
            self.base_actions[e] = base;
        }
        out
    }
}

impl VecEnvironment for GraspVecEnv {
    fn n_envs(&self) -> usize {
        self.baselines.len()
    }
    fn obs_dim(&self) -> usize {
        self.agent.input_dim()
    }
    fn act_dim(&self) -> usize {
        ACT_DIM
    }

    fn reset(&mut self) -> Vec<Vec<f32>> {
        self.raw_obs = self.inner.reset().expect("the grasp env resets");
        for b in self.baselines.iter_mut().flatten() {
            self.episode += 1;
            b.reset(self.episode);
        }
        self.returns.iter_mut().for_each(|r| *r = 0.0);
        self.lengths.iter_mut().for_each(|l| *l = 0);
        self.inputs()
    }

    fn step(&mut self, actions: &[Vec<f32>]) -> StepBatch {
        let env_actions: Vec<Action> = actions
            .iter()
            .zip(&self.base_actions)
            .map(|(a, b)| self.agent.compose(b.as_ref(), a))
            .collect();
        let step = self.inner.step(&env_actions).expect("the grasp env steps");
        let mut out = StepBatch::default();
        for e in 0..self.baselines.len() {
            self.returns[e] += step.rewards[e] as f32;
            self.lengths[e] += 1;
            let done = step.terminated[e] || step.truncated[e];
            out.rewards.push(step.rewards[e] as f32);
            out.terminated.push(step.terminated[e]);
            out.truncated.push(step.truncated[e]);
            if done {
                // The final observation with the baseline action the policy would have seen.
                let final_obs =
                    step.final_obs[e].expect("an ended episode keeps its final observation");
                let base = self.baselines[e].as_mut().map(|b| b.act(&final_obs));
                out.final_obs
                    .push(Some(self.agent.input(&final_obs.to_array(), base.as_ref())));
                out.finished.push(Some(EpisodeStats {
                    success: step.infos[e].success,
                    episode_return: self.returns[e],
                    length: self.lengths[e],
                }));
                self.returns[e] = 0.0;
                self.lengths[e] = 0;
                if let Some(b) = &mut self.baselines[e] {
                    self.episode += 1;
                    b.reset(self.episode);
                }
            } else {
                out.final_obs.push(None);
                out.finished.push(None);
            }
        }
        self.raw_obs = step.obs;
        out.obs = self.inputs();
        out
    }
}
