//! The script a residual agent works on top of, one per env.
//!
//! - [`Script::Joint`] (`action_space = "joint"`, the first residual): the baseline acts first;
//!   its joint-velocity action is appended to the policy input and the policy's output is added
//!   to it (`clip(a_base + scale · a_policy)`).
//! - [`Script::Task`] (`action_space = "tcp"`, the residual with authority): the task's residual
//!   interface ([`TaskResidual`], registered per task in [`fairgrasp_planner::tasks`]) turns the
//!   policy's output into the env's action and adds its features to the policy input — on the
//!   lift task the grasp script's correction and close timing
//!   ([`fairgrasp_planner::lift::residual`]), on the place task the force-guided search's
//!   ([`fairgrasp_planner::place::residual`]).

use fairgrasp_env::episode::Outcome;
use fairgrasp_env::episode::Policy;
use fairgrasp_env::{Action, EnvConfig, Observation};
use fairgrasp_planner::task_residual::{FEATURE_DIM, OUTPUT_DIM};
use fairgrasp_planner::{BaselineConfig, ScriptedGrasp, TaskResidual};

/// One env's script.
pub enum Script {
    Joint(Box<ScriptedGrasp>),
    Task(Box<dyn TaskResidual>),
}

impl Script {
    /// The joint-space baseline.
    pub fn joint(env: &EnvConfig) -> Script {
        Script::Joint(Box::new(ScriptedGrasp::new(env, BaselineConfig::default())))
    }

    /// The residual interface of `env`'s task, with the squeeze if `squeeze` (where the task's
    /// interface has one).
    pub fn task(env: &EnvConfig, squeeze: bool) -> Script {
        Script::Task(fairgrasp_planner::tasks::task_residual(env, squeeze))
    }

    /// The grip force per finger \[N\] the task script's squeeze asks for (None otherwise).
    pub fn grip_force(&self) -> Option<f64> {
        match self {
            Script::Joint(_) => None,
            Script::Task(r) => r.grip_force(),
        }
    }

    pub fn reset(&mut self, seed: u64) {
        match self {
            Script::Joint(b) => (**b).reset(seed),
            Script::Task(r) => r.reset(seed),
        }
    }

    /// What the script does before the policy decides at `obs`: the joint baseline acts (its
    /// action is part of the policy input and of the env action); the task script waits for the
    /// policy's correction.
    pub fn prepare(&mut self, obs: &Observation) -> Option<Action> {
        match self {
            Script::Joint(b) => Some((**b).act(obs)),
            Script::Task(_) => None,
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
            Script::Task(r) => {
                let mut f = [0.0; FEATURE_DIM];
                r.write_features(obs, &mut f);
                for (slot, v) in out.iter_mut().zip(f) {
                    *slot = v as f32;
                }
            }
        }
    }

    /// The task script's env action for the policy's output (None for the joint baseline,
    /// whose action is composed by the agent).
    pub fn act_on(&mut self, obs: &Observation, policy: &[f32]) -> Option<Action> {
        match self {
            Script::Joint(_) => None,
            Script::Task(r) => Some(r.act(obs, &policy_action(policy))),
        }
    }

    /// The script's phase (for recorded trajectories).
    pub fn phase(&self) -> &'static str {
        match self {
            Script::Joint(b) => (**b).phase().name(),
            Script::Task(r) => r.phase(),
        }
    }

    /// Set when the script has given up (no IK solution).
    pub fn gave_up(&self) -> Option<Outcome> {
        match self {
            Script::Joint(b) => (**b).gave_up(),
            Script::Task(r) => r.gave_up(),
        }
    }
}

/// The policy's output as the values a task-space script reads (a missing one counts as 0).
fn policy_action(policy: &[f32]) -> [f64; OUTPUT_DIM] {
    std::array::from_fn(|i| policy.get(i).copied().unwrap_or(0.0) as f64)
}
