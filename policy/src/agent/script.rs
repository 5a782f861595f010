//! The script a residual agent works on top of, one per env.
//!
//! - [`Script::Joint`] (`action_space = "joint"`, the first residual): the baseline acts first;
//!   its joint-velocity action is appended to the policy input and the policy's output is added
//!   to it (`clip(a_base + scale · a_policy)`).
//! - [`Script::Task`] (`action_space = "tcp"`, the residual with authority): the policy's output
//!   is the rate of a task-space correction the script's reference follows, and the close's
//!   timing ([`fairgrasp_planner::residual`]); the script's phase, the cube's motion since the
//!   plan and the correction so far are appended to the policy input.
//! - [`Script::Place`] (`action_space = "tcp"` on a place preset): the same on the place task,
//!   correcting the force-guided search ([`fairgrasp_planner::place_residual`]).

use fairgrasp_env::episode::Outcome;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::{Action, EnvConfig, Observation};
use fairgrasp_planner::residual::{FEATURE_DIM, ResidualScript};
use fairgrasp_planner::{BaselineConfig, PlaceResidual, ScriptedGrasp};

/// One env's script.
pub enum Script {
    Joint(Box<ScriptedGrasp>),
    Task(Box<ResidualScript>),
    Place(Box<PlaceResidual>),
}

impl Script {
    /// The joint-space baseline.
    pub fn joint(env: &EnvConfig) -> Script {
        Script::Joint(Box::new(ScriptedGrasp::new(env, BaselineConfig::default())))
    }

    /// The task-space residual interface, with the squeeze if `squeeze`.
    pub fn task(env: &EnvConfig, squeeze: bool) -> Script {
        let r = ResidualScript::new(env);
        Script::Task(Box::new(if squeeze { r.squeezing(env) } else { r }))
    }

    /// The place task's residual interface on the force-guided search.
    pub fn place(env: &EnvConfig) -> Script {
        Script::Place(Box::new(PlaceResidual::new(env)))
    }

    /// The grip force per finger \[N\] the task script's squeeze asks for (None otherwise).
    pub fn grip_force(&self) -> Option<f64> {
        match self {
            Script::Joint(_) | Script::Place(_) => None,
            Script::Task(r) => r.grip_force(),
        }
    }

    pub fn reset(&mut self, seed: u64) {
        match self {
            Script::Joint(b) => (**b).reset(seed),
            Script::Task(r) => r.reset(seed),
            Script::Place(r) => r.reset(seed),
        }
    }

    /// What the script does before the policy decides at `obs`: the joint baseline acts (its
    /// action is part of the policy input and of the env action); the task script waits for the
    /// policy's correction.
    pub fn prepare(&mut self, obs: &Observation) -> Option<Action> {
        match self {
            Script::Joint(b) => Some((**b).act(obs)),
            Script::Task(_) | Script::Place(_) => None,
        }
    }

    /// Appends the script's part of the policy input at `obs` (`base` is what `prepare`
    /// returned) to `out`: the baseline's 7 action values, or the task script's features.
    pub fn write_input(&self, obs: &Observation, base: Option<&Action>, out: &mut [f32]) {
        match self {
            Script::Joint(_) => {
                let base = base.map_or([0.0; 7], |b| b.0.map(|v| v as f32));
                for (slot, v) in out.iter_mut().zip(base) {
                    *slot = v;
                }
            }
            Script::Task(r) => write_features(|f| r.write_features(obs, f), out),
            Script::Place(r) => write_features(|f| r.write_features(obs, f), out),
        }
    }

    /// The task script's env action for the policy's output (None for the joint baseline,
    /// whose action is composed by the agent).
    pub fn act_on(&mut self, obs: &Observation, policy: &[f32]) -> Option<Action> {
        match self {
            Script::Joint(_) => None,
            Script::Task(r) => Some(r.act(obs, &policy_action(policy))),
            Script::Place(r) => Some(r.act(obs, &policy_action(policy))),
        }
    }

    /// The script's phase (for recorded trajectories).
    pub fn phase(&self) -> &'static str {
        match self {
            Script::Joint(b) => (**b).phase().name(),
            Script::Task(r) => r.script().phase().name(),
            Script::Place(r) => r.phase(),
        }
    }

    /// Set when the script has given up (no IK solution).
    pub fn gave_up(&self) -> Option<Outcome> {
        match self {
            Script::Joint(b) => (**b).gave_up(),
            Script::Task(r) => r.script().gave_up(),
            Script::Place(r) => r.gave_up(),
        }
    }
}

/// The features `write` fills, as policy input values into `out`.
fn write_features(write: impl FnOnce(&mut [f64; FEATURE_DIM]), out: &mut [f32]) {
    let mut f = [0.0; FEATURE_DIM];
    write(&mut f);
    for (slot, v) in out.iter_mut().zip(f) {
        *slot = v as f32;
    }
}

/// The policy's output as the 7 values a task-space script reads (a missing one counts as 0).
fn policy_action(policy: &[f32]) -> [f64; 7] {
    std::array::from_fn(|i| policy.get(i).copied().unwrap_or(0.0) as f64)
}
