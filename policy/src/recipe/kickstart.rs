//! `[kickstart]` of a recipe: the teachers a run's policy is also pulled towards, one trained
//! policy per preset it trains on, and the weight of their term. Loading the teachers is the
//! trainer's (`fairgrasp-rl`'s `run::kickstart`).

use serde::{Deserialize, Serialize};

/// `[kickstart]`: the teachers and the weight of their term.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KickstartConfig {
    /// One teacher per preset trained on, in the order `preset`, `mix[0]`, `mix[1]`, …: a
    /// shipped policy's name, a checkpoint folder or a run folder (relative to the working
    /// directory).
    pub teachers: Vec<String>,
    /// The term's weight at the start of training, in (0, 1000].
    pub weight: f64,
    /// Lower the weight linearly to 0 at the end of training (default: keep it).
    #[serde(default)]
    pub anneal: bool,
}

impl KickstartConfig {
    /// Checks the numbers and that there is a teacher for each of `presets` presets.
    pub fn check(&self, presets: usize) -> Result<(), String> {
        if !(self.weight > 0.0 && self.weight <= 1000.0) {
            return Err(format!(
                "kickstart.weight = {}: must be in (0, 1000]",
                self.weight
            ));
        }
        if self.teachers.len() != presets {
            return Err(format!(
                "kickstart.teachers: {} given, the run trains on {presets} presets (preset, then mix): one teacher each",
                self.teachers.len()
            ));
        }
        Ok(())
    }
}
