//! The grasping agent: residual corrections on top of the scripted baseline, or pure PPO.
//!
//! Residual mode: the policy sees the observation and the baseline's action,
//! `input = obs ⊕ a_base`, and the env receives `clip(a_base + scale · a_policy)`. The actor's
//! output layer starts at zero, so an untrained agent *is* the baseline. With
//! `gripper = "learned"` the gripper command is the policy's own output, not a correction.
//! Pure mode (the seed's setup): `input = obs`, the env receives `clip(a_policy)`.

use fairgrasp_env::config::ActionSpace;
use fairgrasp_env::policy::Policy;
use fairgrasp_env::{Action, EnvConfig, Observation};

use crate::action_map::ActionMap;
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp};
use serde::{Deserialize, Serialize};

/// Residual or pure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// Corrections on top of the scripted baseline.
    #[default]
    Residual,
    /// No baseline: the seed recipe's PPO.
    Pure,
}

impl std::fmt::Display for Mode {
    /// The config's name: `residual` or `pure`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Mode::Residual => "residual",
            Mode::Pure => "pure",
        })
    }
}

/// Who commands the gripper in residual mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum GripperMode {
    /// The baseline's command plus a correction.
    #[default]
    Residual,
    /// The policy's own output.
    Learned,
}

impl std::fmt::Display for GripperMode {
    /// The config's name: `residual` or `learned`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            GripperMode::Residual => "residual",
            GripperMode::Learned => "learned",
        })
    }
}

/// How the policy's output becomes an env action.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AgentConfig {
    pub mode: Mode,
    /// Scale of the residual (action units per policy unit).
    pub residual_scale: f32,
    pub gripper: GripperMode,
    /// What the policy's output commands: `joint` velocities (the seed's) or the TCP's velocity
    /// and yaw rate (`tcp`, pure mode only; [`crate::action_map`]).
    pub action_space: ActionSpace,
}

impl Default for AgentConfig {
    fn default() -> Self {
        Self {
            mode: Mode::Residual,
            residual_scale: 0.3,
            gripper: GripperMode::Residual,
            action_space: ActionSpace::Joint,
        }
    }
}

/// Env observation size.
pub const OBS_DIM: usize = fairgrasp_env::obs::OBS_DIM;
/// Env action size.
pub const ACT_DIM: usize = 7;

impl AgentConfig {
    /// The policy's input size.
    pub fn input_dim(&self) -> usize {
        match self.mode {
            Mode::Residual => OBS_DIM + ACT_DIM,
            Mode::Pure => OBS_DIM,
        }
    }

    /// Writes the policy input for a typed observation and (residual mode) the baseline's
    /// action into `out` (`input_dim` values: the observation's flat view in the order of
    /// `fairgrasp_env::obs::OBS_NAMES`, then the baseline's 7 action values, 0 if none).
    ///
    /// The one place a policy input is built: training, episode ends and evaluation all call it
    /// with the environment's own `Observation`.
    pub fn write_input(&self, obs: &Observation, base: Option<&Action>, out: &mut [f32]) {
        let obs = obs.to_array();
        let base = base.map_or([0.0; ACT_DIM], |b| b.0.map(|v| v as f32));
        let extra: &[f32] = match self.mode {
            Mode::Residual => &base,
            Mode::Pure => &[],
        };
        for (slot, v) in out.iter_mut().zip(obs.iter().chain(extra)) {
            *slot = *v;
        }
    }

    /// [`AgentConfig::write_input`] into a new vector.
    pub fn input(&self, obs: &Observation, base: Option<&Action>) -> Vec<f32> {
        let mut x = vec![0.0; self.input_dim()];
        self.write_input(obs, base, &mut x);
        x
    }

    /// The env action for the policy's output (`ACT_DIM` values; a missing one counts as 0).
    pub fn compose(&self, base: Option<&Action>, policy: &[f32]) -> Action {
        Action(std::array::from_fn(|i| {
            let p = policy.get(i).copied().unwrap_or(0.0) as f64;
            let v = match (self.mode, base) {
                (Mode::Residual, Some(_)) if i == 6 && self.gripper == GripperMode::Learned => p,
                (Mode::Residual, Some(b)) => b.0[i] + self.residual_scale as f64 * p,
                _ => p,
            };
            v.clamp(-1.0, 1.0)
        }))
    }

    /// The map from the policy's task-space output to joint actions (`tcp` mode only).
    pub fn action_map(&self, env: &EnvConfig) -> Option<ActionMap> {
        (self.action_space == ActionSpace::Tcp).then(|| ActionMap::new(env))
    }

    /// The env action for the policy's output at observation `obs`: [`AgentConfig::compose`],
    /// then, in `tcp` mode, through `map` to joint velocities.
    pub fn env_action(
        &self,
        obs: &Observation,
        base: Option<&Action>,
        policy: &[f32],
        map: Option<&ActionMap>,
    ) -> Action {
        let action = self.compose(base, policy);
        match map {
            Some(map) => map.to_joint_action(&obs.joints, &action),
            None => action,
        }
    }

    /// A baseline for residual mode.
    pub fn baseline(&self, env: &EnvConfig) -> Option<ScriptedGrasp> {
        (self.mode == Mode::Residual).then(|| ScriptedGrasp::new(env, BaselineConfig::default()))
    }
}

/// Maps a raw policy input to the mean policy output.
pub type MeanAction = Box<dyn Fn(&[f32]) -> Vec<f32> + Send>;

/// A trained (or fresh) agent as a [`Policy`]: deterministic, mean actions.
pub struct GraspAgent {
    pub agent: AgentConfig,
    baseline: Option<ScriptedGrasp>,
    action_map: Option<ActionMap>,
    mean_action: MeanAction,
}

impl GraspAgent {
    /// `mean_action` maps a raw policy input to the mean policy output.
    pub fn new(agent: AgentConfig, env: &EnvConfig, mean_action: MeanAction) -> Self {
        Self {
            baseline: agent.baseline(env),
            action_map: agent.action_map(env),
            agent,
            mean_action,
        }
    }
}

impl Policy for GraspAgent {
    fn reset(&mut self, seed: u64) {
        if let Some(b) = &mut self.baseline {
            b.reset(seed);
        }
    }

    fn act(&mut self, obs: &Observation) -> Action {
        let base = self.baseline.as_mut().map(|b| b.act(obs));
        let input = self.agent.input(obs, base.as_ref());
        let out = (self.mean_action)(&input);
        self.agent
            .env_action(obs, base.as_ref(), &out, self.action_map.as_ref())
    }

    fn gave_up(&self) -> Option<fairgrasp_env::policy::Outcome> {
        self.baseline.as_ref().and_then(|b| b.gave_up())
    }
}
