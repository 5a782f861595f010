//! An episode's record, gathered step by step by the env and finished at its terminal step: the
//! facts ([`EpisodeFacts`]) its outcome is decided from, the return, and the collision pair.
//! The record's type and the outcome rule are `fairgrasp_types::episode`'s.

use fairgrasp_types::{EpisodeFacts, EpisodeRecord};

use crate::task::judge::Failure;

/// The object must rise this far above rest while both pads touch it to count as lifted \[m\].
const LIFTED: f64 = 0.01;
/// The gripper counts as closed past the object below its size minus this \[m\].
const CLOSED_PAST: f64 = 0.005;

/// What an episode has shown so far.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EpisodeTracker {
    /// The object's height at rest after the reset, `base_link` z \[m\].
    object_rest_z: f64,
    /// The object's edge length \[m\].
    object_size: f64,
    facts: EpisodeFacts,
    episode_return: f64,
}

/// One step as the tracker needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepFacts {
    /// Left and right pad touching the object.
    pub pad_contact: [bool; 2],
    /// The object's height, `base_link` z \[m\].
    pub object_z: f64,
    /// Distance between the pads \[m\].
    pub gripper_opening: f64,
    pub reward: f64,
}

/// How the terminal step ended the episode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ending<'a> {
    /// Scenario seed and the object's start in the table frame \[m\].
    pub seed: u64,
    pub object_xy: [f64; 2],
    /// Steps taken, each `step_seconds` of simulated time \[s\].
    pub steps: usize,
    pub step_seconds: f64,
    /// The task's takt \[s\], if it runs on one.
    pub takt: Option<f64>,
    pub success: bool,
    pub failure: Option<&'a Failure>,
    pub physics_fault: bool,
}

impl EpisodeTracker {
    /// A new episode whose object rests at `object_rest_z` (`base_link` z) \[m\].
    pub fn start(object_rest_z: f64, object_size: f64) -> Self {
        Self {
            object_rest_z,
            object_size,
            ..Self::default()
        }
    }

    /// Takes one step into account.
    pub fn observe(&mut self, step: StepFacts) {
        let both = step.pad_contact[0] && step.pad_contact[1];
        let f = &mut self.facts;
        f.held |= both;
        f.lifted |= both && step.object_z - self.object_rest_z > LIFTED;
        f.closed_past_object |= step.gripper_opening < self.object_size - CLOSED_PAST;
        self.episode_return += step.reward;
    }

    /// The record of an episode that ended as `ending` says.
    pub fn finish(&self, ending: Ending) -> EpisodeRecord {
        let mut facts = EpisodeFacts {
            success: ending.success,
            physics_fault: ending.physics_fault,
            ..self.facts
        };
        let collision_pair = match ending.failure {
            Some(Failure::Collision(a, b)) => {
                facts.collision = true;
                Some([a.clone(), b.clone()])
            }
            Some(Failure::ProtectiveStop {
                robot_part,
                other_part,
                ..
            }) => {
                facts.protective_stop = true;
                Some([robot_part.clone(), other_part.clone()])
            }
            Some(Failure::ObjectOffTable) => {
                facts.off_table = true;
                None
            }
            None => None,
        };
        EpisodeRecord {
            seed: ending.seed,
            outcome: facts.outcome(None),
            steps: ending.steps,
            episode_return: self.episode_return,
            object_xy: ending.object_xy,
            collision_pair,
            cycle_time_s: ending
                .success
                .then_some(ending.steps as f64 * ending.step_seconds),
            takt_s: ending.takt,
            facts,
        }
    }
}
