//! The oracle switch ([`OracleSwitch`]): the switching search's two settings
//! (`[task.place.switch]`), applied knowing each cycle's family — what a cell could only do if
//! something told it which error a cycle carries. A ceiling reported beside the controls, never
//! a control: nothing a real cell measures gives the family before the cycle.

use fairgrasp_env::cell::Cell;
use fairgrasp_env::config::SwitchParams;
use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::scenario::Scenario;
use fairgrasp_env::scenario::error_mix::ErrorFamily;
use fairgrasp_env::{Action, EnvConfig, Observation};

use crate::place::script::ScriptedPlace;

/// The place script whose search is set per episode from the scenario's family.
pub struct OracleSwitch {
    inner: ScriptedPlace,
    config: EnvConfig,
    cell: Cell,
    switch: SwitchParams,
    /// The last episode's cycle read as tilted (the family it was told).
    tilted: bool,
}

impl OracleSwitch {
    /// The oracle switch for the env `env` (its `[task.place.switch]`).
    pub fn new(env: &EnvConfig) -> Self {
        let switch = env.task.place.switch;
        Self {
            inner: ScriptedPlace::with_search(env, switch.pose),
            config: env.clone(),
            cell: Cell::from_config(env),
            switch,
            tilted: false,
        }
    }

    /// Does the scenario of `seed` carry a tilted cube? Its family in a mix; without a mix, the
    /// preset's own family (tilted if it turns the cube in the grip).
    pub fn is_tilted(&self, seed: u64) -> bool {
        let family = Scenario::sample_in(&self.cell, &self.config, seed)
            .ok()
            .and_then(|s| s.fixture)
            .and_then(|f| f.error_family);
        match family {
            Some(f) => f == ErrorFamily::Tilted,
            None => self.config.task.place.grip_tilt[1] > 0.0,
        }
    }

    /// Whether the last reset's cycle was told to be a tilted cube's.
    pub fn told_tilted(&self) -> bool {
        self.tilted
    }
}

impl Policy for OracleSwitch {
    fn reset(&mut self, seed: u64) {
        self.tilted = self.is_tilted(seed);
        let s = &self.switch;
        self.inner
            .set_search_params(if self.tilted { s.tilted } else { s.pose });
        self.inner.reset(seed);
    }

    fn act(&mut self, obs: &Observation) -> Action {
        self.inner.act(obs)
    }

    fn gave_up(&self) -> Option<Outcome> {
        self.inner.gave_up()
    }

    fn phase(&self) -> Option<&'static str> {
        Policy::phase(&self.inner)
    }
}
