//! One env's side of an agent: the script a residual agent works on (none in pure mode) and the
//! joint baseline's action for the current observation. The trainer's vectorised env
//! (`fairgrasp_rl::agent::task_vec_env`) and Python's recipe envs (`python/src/agent_env.rs`) step
//! an env through it, so both hand the policy the same input and the env the same action.
//!
//! Per step: [`EnvAgent::observe`] at each observation (the joint baseline acts, the policy
//! input is written), [`EnvAgent::act`] with the policy's output, and at an episode's end
//! [`EnvAgent::verdict`] (the script's own outcome, e.g. no IK solution), then
//! [`EnvAgent::reset`] with the next episode's seed.

use fairgrasp_env::episode::Outcome;
use fairgrasp_env::robot::tcp_action::TaskSpaceAction;
use fairgrasp_env::{Action, EnvConfig, Observation};

use crate::agent::grasp_agent::AgentConfig;
use crate::agent::script::Script;

/// The script and the baseline's action of one env.
pub struct EnvAgent {
    script: Option<Script>,
    /// The joint baseline's action for the last observed observation (joint residual only).
    base: Option<Action>,
}

impl EnvAgent {
    /// The agent side of one env of `env` (its script per [`AgentConfig::script`]).
    pub fn new(agent: &AgentConfig, env: &EnvConfig) -> Self {
        Self {
            script: agent.script(env),
            base: None,
        }
    }

    /// Starts the script's episode `seed` (the env's scenario seed).
    pub fn reset(&mut self, seed: u64) {
        if let Some(s) = &mut self.script {
            s.reset(seed);
        }
        self.base = None;
    }

    /// What the script does at `obs` before the policy decides ([`Script::prepare`]), and the
    /// policy input for it written into `out` ([`AgentConfig::write_input`], `input_dim`
    /// values).
    pub fn observe(&mut self, agent: &AgentConfig, obs: &Observation, out: &mut [f32]) {
        self.base = self.script.as_mut().and_then(|s| s.prepare(obs));
        agent.write_input(obs, self.script.as_ref(), self.base.as_ref(), out);
    }

    /// The env action for the policy's output at `obs` (the observation last observed):
    /// [`AgentConfig::env_action`].
    pub fn act(
        &mut self,
        agent: &AgentConfig,
        obs: &Observation,
        policy: &[f32],
        task_space: Option<&TaskSpaceAction>,
    ) -> Action {
        agent.env_action(
            obs,
            self.script.as_mut(),
            self.base.as_ref(),
            policy,
            task_space,
        )
    }

    /// The grip force per finger \[N\] the script's squeeze asks for after the latest `act`
    /// (None without the squeeze): hand it to the env before the step.
    pub fn grip_force(&self) -> Option<f64> {
        self.script.as_ref().and_then(Script::grip_force)
    }

    /// The joint baseline's action for the last observation (None in pure mode and for a
    /// task-space residual).
    pub fn base_action(&self) -> Option<&Action> {
        self.base.as_ref()
    }

    /// The script's verdict on the episode (it gave up), which outranks the env's lesser
    /// outcomes ([`fairgrasp_env::episode::Outcome`]); None in pure mode.
    pub fn verdict(&self) -> Option<Outcome> {
        self.script.as_ref().and_then(|s| s.gave_up())
    }
}

/// The bounds of a policy input's script part ([`AgentConfig::input_names`] after the
/// observation's), given `object_bound`: a bound on every coordinate of the observed cube's
/// position in `base_link` \[m\] (the observation space's). Empty in pure mode.
pub fn script_input_bounds(
    agent: &AgentConfig,
    env: &EnvConfig,
    object_bound: f64,
) -> Vec<(f64, f64)> {
    match agent.script(env) {
        None => Vec::new(),
        Some(Script::Joint(_)) => vec![(-1.0, 1.0); fairgrasp_env::env::spaces::ACT_DIM],
        Some(Script::Task(r)) => r.feature_bounds(object_bound).to_vec(),
    }
}

/// The names of a policy output's entries, in order: what each commands on the env of
/// `env` (for a pure agent, the env's action; for a residual, its correction).
pub fn output_names(agent: &AgentConfig, env: &EnvConfig) -> Vec<String> {
    use fairgrasp_env::env::spaces::action_space_of;
    let env_names = || -> Vec<String> {
        action_space_of(agent.env_for(env).arm.action_space)
            .names
            .iter()
            .map(|n| n.to_string())
            .collect()
    };
    match agent.script(env) {
        None => env_names(),
        Some(Script::Joint(_)) => env_names()
            .into_iter()
            .enumerate()
            .map(|(i, n)| {
                if i == 6 && agent.gripper == crate::agent::GripperMode::Learned {
                    n
                } else {
                    format!("{n}_correction")
                }
            })
            .collect(),
        Some(Script::Task(r)) => r.output_names().map(String::from).to_vec(),
    }
}
