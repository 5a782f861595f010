//! The grasping agent: residual corrections on top of the scripted baseline, or pure PPO.
//!
//! Residual mode, `action_space = "joint"` (the first residual): the policy sees the observation
//! and the baseline's action, `input = obs ⊕ a_base`, and the env receives
//! `clip(a_base + scale · a_policy)`. With `gripper = "learned"` the gripper command is the
//! policy's own output, not a correction.
//! Residual mode, `action_space = "tcp"` (the residual with authority): the policy sees
//! `obs ⊕ script features` and its output is the rate of a task-space correction of the script
//! plus the close's timing ([`crate::agent::script`], [`fairgrasp_planner::lift::residual`]).
//! Either way the actor's output layer can start at zero, so an untrained agent *is* the script.
//! Pure mode (the seed's setup): `input = obs`, the env receives `clip(a_policy)`, or in `tcp`
//! mode the TCP velocity it commands, through the env's task-space action
//! ([`fairgrasp_env::robot::tcp_action::TaskSpaceAction`]).

use fairgrasp_env::cell::Cell;
use fairgrasp_env::config::{ActionSpace, GripperCommand, TcpSaturation};
use fairgrasp_env::episode::Policy;
use fairgrasp_env::robot::tcp_action::TaskSpaceAction;
use fairgrasp_env::{Action, EnvConfig, Observation};

use crate::agent::script::Script;
use fairgrasp_planner::lift::residual::FEATURE_DIM;
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
    /// What the policy's output commands: `joint` velocities (the seed's; in residual mode, a
    /// correction of the baseline's), or in task space (`tcp`): the TCP's velocity and yaw rate
    /// in pure mode (the env's `TaskSpaceAction`), the rate of a correction of the script's grasp in
    /// residual mode ([`crate::agent::script`]).
    pub action_space: ActionSpace,
    /// A task-space residual also commands the grip force with its output's entry 4
    /// ([`fairgrasp_planner::lift::residual`]); off by default (earlier policies' entry 4 is
    /// unused).
    pub squeeze: bool,
}

impl Default for AgentConfig {
    fn default() -> Self {
        Self {
            mode: Mode::Residual,
            residual_scale: 0.3,
            gripper: GripperMode::Residual,
            action_space: ActionSpace::Joint,
            squeeze: false,
        }
    }
}

/// Env observation size.
pub const OBS_DIM: usize = fairgrasp_env::env::obs::OBS_DIM;
/// Env action size (the env's).
pub use fairgrasp_env::env::spaces::ACT_DIM;

impl AgentConfig {
    /// Checks the numbers (the residual's scale in (0, 10]) and that only a task-space residual
    /// has the squeeze; the message names the field.
    pub fn check(&self) -> Result<(), String> {
        if self.squeeze && !self.task_residual() {
            return Err(format!(
                "agent.squeeze = true needs mode = \"residual\" and action_space = \"tcp\" (got mode = \"{}\", action_space = \"{}\")",
                self.mode,
                match self.action_space {
                    ActionSpace::Joint => "joint",
                    ActionSpace::Tcp => "tcp",
                }
            ));
        }
        if !(self.residual_scale > 0.0 && self.residual_scale <= 10.0) {
            let v = self.residual_scale;
            let shown = if v.abs() >= 1e6 {
                format!("{v:e}")
            } else {
                v.to_string()
            };
            return Err(format!(
                "agent.residual_scale = {shown}: must be in (0, 10]"
            ));
        }
        Ok(())
    }

    /// The policy's input size.
    pub fn input_dim(&self) -> usize {
        match (self.mode, self.action_space) {
            (Mode::Residual, ActionSpace::Joint) => OBS_DIM + ACT_DIM,
            (Mode::Residual, ActionSpace::Tcp) => OBS_DIM + FEATURE_DIM,
            (Mode::Pure, _) => OBS_DIM,
        }
    }

    /// Whether the residual corrects the script in task space.
    fn task_residual(&self) -> bool {
        self.mode == Mode::Residual && self.action_space == ActionSpace::Tcp
    }

    /// Writes the policy input for a typed observation into `out` (`input_dim` values: the
    /// observation's flat view in the order of `fairgrasp_env::env::obs::OBS_NAMES`, then in residual
    /// mode the script's part ([`Script::write_input`]: the baseline's 7 action values, 0 if
    /// none, or the task script's features)).
    ///
    /// The one place a policy input is built: training, episode ends and evaluation all call it
    /// with the environment's own `Observation`.
    pub fn write_input(
        &self,
        obs: &Observation,
        script: Option<&Script>,
        base: Option<&Action>,
        out: &mut [f32],
    ) {
        let flat = obs.to_array();
        for (slot, v) in out.iter_mut().zip(flat) {
            *slot = v;
        }
        if self.mode == Mode::Residual {
            let rest = &mut out[OBS_DIM..];
            match script {
                Some(s) => s.write_input(obs, base, rest),
                None => rest.fill(0.0),
            }
        }
    }

    /// The names of the policy input's entries on the env of `env`, in order: the
    /// observation's ([`fairgrasp_env::env::obs::OBS_NAMES`]), then the script's part
    /// (`baseline_action_0` … `_6`, or the task script's features:
    /// [`fairgrasp_planner::TaskResidual::feature_names`] of the env's task).
    pub fn input_names(&self, env: &EnvConfig) -> Vec<String> {
        let mut names: Vec<String> = fairgrasp_env::env::obs::OBS_NAMES
            .iter()
            .map(|n| n.to_string())
            .collect();
        match (self.mode, self.action_space) {
            (Mode::Pure, _) => {}
            (Mode::Residual, ActionSpace::Joint) => {
                names.extend((0..ACT_DIM).map(|i| format!("baseline_action_{i}")));
            }
            (Mode::Residual, ActionSpace::Tcp) => {
                let residual = fairgrasp_planner::tasks::task_residual(env, self.squeeze);
                names.extend(residual.feature_names().iter().map(|n| n.to_string()));
            }
        }
        names
    }

    /// The input entries whose names start with `prefix` on the env of `env` (an ablation
    /// masks them), or an error listing the names.
    pub fn input_indices(&self, env: &EnvConfig, prefix: &str) -> Result<Vec<usize>, String> {
        let names = self.input_names(env);
        let found: Vec<usize> = (0..names.len())
            .filter(|&i| !prefix.is_empty() && names[i].starts_with(prefix))
            .collect();
        if found.is_empty() {
            return Err(format!(
                "no policy input starts with `{prefix}`; the inputs are: {}",
                names.join(", ")
            ));
        }
        Ok(found)
    }

    /// [`AgentConfig::write_input`] into a new vector.
    pub fn input(
        &self,
        obs: &Observation,
        script: Option<&Script>,
        base: Option<&Action>,
    ) -> Vec<f32> {
        let mut x = vec![0.0; self.input_dim()];
        self.write_input(obs, script, base, &mut x);
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

    /// Whether the policy commands the TCP directly (pure mode, `tcp` action space).
    fn pure_task_space(&self) -> bool {
        self.mode == Mode::Pure && self.action_space == ActionSpace::Tcp
    }

    /// The env a policy of this agent acts on directly, its output handed over as it is: for
    /// a pure `tcp` agent, `env` with the env's task-space action saturated at
    /// `arm.action_scale` and a binary gripper (`arm.action_space = "tcp"`,
    /// `tcp_saturation = "action_scale"`, `gripper_command = "binary"`); otherwise `env`.
    pub fn env_for(&self, env: &EnvConfig) -> EnvConfig {
        let mut env = env.clone();
        if self.pure_task_space() {
            env.arm.action_space = ActionSpace::Tcp;
            env.arm.tcp_saturation = TcpSaturation::ActionScale;
            env.arm.gripper_command = GripperCommand::Binary;
        }
        env
    }

    /// The env's task-space action of [`AgentConfig::env_for`] (pure `tcp` mode only), for
    /// acting on a `joint`-mode env: it turns the policy's output into joint actions.
    pub fn task_space(&self, env: &EnvConfig) -> Option<TaskSpaceAction> {
        self.pure_task_space().then(|| {
            let direct = self.env_for(env);
            TaskSpaceAction::new(&Cell::from_config(&direct), &direct.arm)
        })
    }

    /// The env action for the policy's output at observation `obs`: the task script's action
    /// for a task-space residual; otherwise [`AgentConfig::compose`], then, in pure `tcp` mode,
    /// through the env's `task_space` action to joint velocities.
    pub fn env_action(
        &self,
        obs: &Observation,
        script: Option<&mut Script>,
        base: Option<&Action>,
        policy: &[f32],
        task_space: Option<&TaskSpaceAction>,
    ) -> Action {
        if let Some(action) = script.and_then(|s| s.act_on(obs, policy)) {
            return action;
        }
        let action = self.compose(base, policy);
        match task_space {
            Some(t) => Action(t.to_joint_action(&obs.joints, &action.0)),
            None => action,
        }
    }

    /// The script for residual mode (None in pure mode): a task-space residual corrects the
    /// residual interface of the env's task ([`fairgrasp_planner::tasks::task_residual`]; on a
    /// place preset the force-guided search, where the squeeze is not used).
    pub fn script(&self, env: &EnvConfig) -> Option<Script> {
        match self.mode {
            Mode::Pure => None,
            Mode::Residual if self.task_residual() => Some(Script::task(env, self.squeeze)),
            Mode::Residual => Some(Script::joint(env)),
        }
    }
}

/// Maps a raw policy input to the mean policy output.
pub type MeanAction = Box<dyn Fn(&[f32]) -> Vec<f32> + Send>;

/// A trained (or fresh) agent as a [`Policy`]: deterministic, mean actions.
pub struct GraspAgent {
    pub agent: AgentConfig,
    script: Option<Script>,
    task_space: Option<TaskSpaceAction>,
    mean_action: MeanAction,
    /// Input entries set to 0 before the policy sees them (an ablation).
    masked: Vec<usize>,
}

impl GraspAgent {
    /// `mean_action` maps a raw policy input to the mean policy output.
    pub fn new(agent: AgentConfig, env: &EnvConfig, mean_action: MeanAction) -> Self {
        Self {
            script: agent.script(env),
            task_space: agent.task_space(env),
            agent,
            mean_action,
            masked: Vec::new(),
        }
    }

    /// The same agent with the input entries `masked` (indices, see
    /// [`AgentConfig::input_indices`]) set to 0 — for a residual's features, what it sees when
    /// they carry no information (no push, no wrist view). An ablation: what is the policy
    /// worth without them?
    pub fn with_masked_inputs(mut self, masked: Vec<usize>) -> Self {
        self.masked = masked;
        self
    }
}

impl Policy for GraspAgent {
    fn reset(&mut self, seed: u64) {
        if let Some(s) = &mut self.script {
            s.reset(seed);
        }
    }

    fn act(&mut self, obs: &Observation) -> Action {
        let base = self.script.as_mut().and_then(|s| s.prepare(obs));
        let mut input = self.agent.input(obs, self.script.as_ref(), base.as_ref());
        for &i in &self.masked {
            if let Some(v) = input.get_mut(i) {
                *v = 0.0;
            }
        }
        let out = (self.mean_action)(&input);
        self.agent.env_action(
            obs,
            self.script.as_mut(),
            base.as_ref(),
            &out,
            self.task_space.as_ref(),
        )
    }

    fn gave_up(&self) -> Option<fairgrasp_env::episode::Outcome> {
        self.script.as_ref().and_then(|s| s.gave_up())
    }

    fn phase(&self) -> Option<&'static str> {
        self.script.as_ref().map(Script::phase)
    }

    fn grip_force(&self) -> Option<f64> {
        self.script.as_ref().and_then(Script::grip_force)
    }
}
