//! The open-loop script with the grip an engineer tuned for the cell ([`TunedGripScript`]): the
//! control a learned squeeze must beat on the contact family. The grip force comes from the
//! preset's `[control] grip_force`, found by a grid search on training scenarios
//! (docs/contact.md); where none is tuned, this control is the open-loop script itself.

use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::{Action, EnvConfig, Observation};

use crate::lift::script::{BaselineConfig, ScriptedGrasp};

/// The open-loop script squeezing `control.grip_force` per finger, as a [`Policy`].
pub struct TunedGripScript {
    script: ScriptedGrasp,
    /// Squeeze per finger \[N\]; `None`: the env's `gripper.force`.
    grip_force: Option<f64>,
}

impl TunedGripScript {
    /// The control for the cell `env` describes (its `[control] grip_force`).
    pub fn new(env: &EnvConfig) -> Self {
        Self::with_grip(env, env.control.grip_force)
    }

    /// The open-loop script squeezing `grip_force` \[N\] per finger (`None`: `gripper.force`):
    /// one point of the grid an engineer searches.
    pub fn with_grip(env: &EnvConfig, grip_force: Option<f64>) -> Self {
        Self {
            script: ScriptedGrasp::new(env, BaselineConfig::default()),
            grip_force,
        }
    }
}

impl Policy for TunedGripScript {
    fn reset(&mut self, seed: u64) {
        self.script.reset(seed);
    }
    fn act(&mut self, obs: &Observation) -> Action {
        self.script.act(obs)
    }
    fn gave_up(&self) -> Option<Outcome> {
        self.script.gave_up()
    }
    fn phase(&self) -> Option<&'static str> {
        Policy::phase(&self.script)
    }
    fn grip_force(&self) -> Option<f64> {
        self.grip_force
    }
}
