//! The curriculum one env, or a vector of envs, plays under (a recipe's, if it has one), as
//! Python reads and moves it: its stage, a move to another stage, and the ended episodes it
//! counts. Its stage sets the scenario randomisation; the owner applies the randomisation this
//! hands back.

use fairgrasp_env::config::RandomizationConfig;
use fairgrasp_env::scenario::curriculum::Curriculum;
use fairgrasp_env::{EnvError, Info};
use fairgrasp_policy::agent::EnvAgent;

use crate::info::Stage;
use crate::setup::Setup;

/// A recipe's curriculum, or none.
pub(crate) struct EnvCurriculum(Option<Curriculum>);

impl EnvCurriculum {
    /// The curriculum of `setup`, at its first stage.
    pub fn new(setup: &Setup) -> Self {
        Self(setup.curriculum())
    }

    /// The randomisation of the current stage (None without a curriculum).
    pub fn randomization(&self) -> Option<RandomizationConfig> {
        self.0.as_ref().map(Curriculum::randomization)
    }

    /// The current stage, as the info reports it: its index and name.
    pub fn stage(&self) -> Option<Stage> {
        self.0
            .as_ref()
            .map(|c| (c.stage(), c.stage_name(c.stage())))
    }

    /// Moves to `stage` (clamped to the last) with empty windows, once `apply` has taken the new
    /// stage's randomisation; a refusal leaves the curriculum where it was. Nothing to do
    /// without a curriculum.
    pub fn move_to(
        &mut self,
        stage: usize,
        apply: impl FnOnce(RandomizationConfig) -> Result<(), EnvError>,
    ) -> Result<(), EnvError> {
        let Some(current) = &self.0 else {
            return Ok(());
        };
        let moved = current.clone().at_stage(stage);
        apply(moved.randomization())?;
        self.0 = Some(moved);
        Ok(())
    }

    /// Applies the agent's verdict to an ended episode's record and counts the episode; returns
    /// the new randomisation if the stage advanced. The success counted is the record's (as the
    /// trainer counts it).
    pub fn episode_ended(
        &mut self,
        info: &mut Info,
        agent: Option<&EnvAgent>,
    ) -> Option<RandomizationConfig> {
        if let Some(a) = agent {
            info.episode = info
                .episode
                .take()
                .map(|r| r.with_policy_verdict(a.verdict()));
        }
        let c = self.0.as_mut()?;
        let success = info.episode.as_ref().is_some_and(|r| r.success());
        let xy = info.scenario.map(|s| s.object_xy);
        c.record_at(success, xy).then(|| c.randomization())
    }
}
