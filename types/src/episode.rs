//! The one record of a finished episode: computed by the env at the episode's terminal step and
//! read by everything else (evaluation, comparison, training logs, the report, the notebook,
//! Python). What an episode's outcome is, is decided here, once ([`EpisodeFacts::outcome`]).

use serde::{Deserialize, Serialize};

use crate::names::Outcome;

/// What the env saw over an episode, gathered step by step: the facts its outcome is decided
/// from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct EpisodeFacts {
    /// The last step succeeded: lifted at least `task.lift_height`, held between both pads, the
    /// TCP within 3 cm of the object.
    pub success: bool,
    /// The physics state became non-finite (the episode was cut).
    pub physics_fault: bool,
    /// The last step found a collision of arm or gripper (with the table or itself).
    pub collision: bool,
    /// The last step was a protective stop (a robot part pushed the object harder than
    /// `task.protective_stop_force`).
    pub protective_stop: bool,
    /// The object left the table.
    pub off_table: bool,
    /// Both pads touched the object at some step.
    pub held: bool,
    /// The object was more than 1 cm above its resting height while both pads touched it, at
    /// some step.
    pub lifted: bool,
    /// The gripper closed narrower than the object (by more than 5 mm) at some step.
    pub closed_past_object: bool,
}

impl EpisodeFacts {
    /// The episode's outcome, by precedence: success; a physics fault; a collision; a protective
    /// stop; the policy's own verdict (`policy_verdict`: a script that gave up, e.g. no IK
    /// solution); slip or drop (held and lifted, then lost); the object off the table; a missed
    /// grasp (the gripper closed past the object without both pads on it); else a timeout.
    pub fn outcome(&self, policy_verdict: Option<Outcome>) -> Outcome {
        if self.success {
            Outcome::Success
        } else if self.physics_fault {
            Outcome::PhysicsFault
        } else if self.collision {
            Outcome::Collision
        } else if self.protective_stop {
            Outcome::ProtectiveStop
        } else if let Some(verdict) = policy_verdict {
            verdict
        } else if self.lifted {
            Outcome::SlipOrDrop
        } else if self.off_table {
            Outcome::ObjectOffTable
        } else if self.closed_past_object && !self.held {
            Outcome::MissedGrasp
        } else {
            Outcome::Timeout
        }
    }
}

/// One finished episode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRecord {
    /// Scenario seed.
    pub seed: u64,
    /// How it ended ([`EpisodeFacts::outcome`] of `facts`, with the policy's verdict if any).
    pub outcome: Outcome,
    /// Environment steps until the episode ended.
    pub steps: usize,
    /// Sum of the rewards.
    pub episode_return: f64,
    /// Object start position in the table frame \[m\], for workspace maps.
    pub object_xy: [f64; 2],
    /// The two parts of the collision or protective stop that ended it (robot part first for a
    /// stop), by their URDF link names (`table`, `cube` for those).
    #[serde(default)]
    pub collision_pair: Option<[String; 2]>,
    /// The cycle time: simulated time from the reset to the step that succeeded \[s\] (`steps`
    /// times the env step's duration); `None` unless the episode succeeded.
    #[serde(default)]
    pub cycle_time_s: Option<f64>,
    /// The takt the task runs on \[s\] (`[task.place] takt`: a cell's time for one cycle from
    /// the reset); `None` for a task without one (lift).
    #[serde(default)]
    pub takt_s: Option<f64>,
    /// What the env saw (in JSON beside the fields above: `success`, `held`, `lifted`, …).
    #[serde(flatten)]
    pub facts: EpisodeFacts,
}

impl EpisodeRecord {
    /// Whether the episode succeeded (its outcome is [`Outcome::Success`]).
    pub fn success(&self) -> bool {
        self.outcome == Outcome::Success
    }

    /// Succeeded within the takt: a success whose cycle time is at most the takt (any success
    /// for a task without a takt).
    pub fn success_within_takt(&self) -> bool {
        match (self.cycle_time_s, self.takt_s) {
            (Some(cycle), Some(takt)) => self.success() && cycle <= takt,
            _ => self.success(),
        }
    }

    /// The record with the policy's verdict taken into account (it outranks the outcomes below
    /// it, see [`EpisodeFacts::outcome`]); `None` leaves it as the env decided.
    pub fn with_policy_verdict(mut self, verdict: Option<Outcome>) -> Self {
        self.outcome = self.facts.outcome(verdict);
        self
    }

    /// A record read from a file written before the facts were recorded carries only its
    /// outcome: its `success` fact is made to agree with it.
    pub fn normalized(mut self) -> Self {
        self.facts.success = self.outcome == Outcome::Success;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn facts() -> EpisodeFacts {
        EpisodeFacts::default()
    }

    #[test]
    fn each_outcome_follows_from_its_facts_by_precedence() {
        let f = |g: &dyn Fn(&mut EpisodeFacts)| {
            let mut x = facts();
            g(&mut x);
            x
        };
        assert_eq!(facts().outcome(None), Outcome::Timeout);
        let missed = f(&|x| x.closed_past_object = true);
        assert_eq!(missed.outcome(None), Outcome::MissedGrasp);
        let held_closed = f(&|x| {
            x.closed_past_object = true;
            x.held = true;
        });
        assert_eq!(held_closed.outcome(None), Outcome::Timeout);
        let slip = f(&|x| {
            x.held = true;
            x.lifted = true;
            x.off_table = true;
        });
        assert_eq!(
            slip.outcome(None),
            Outcome::SlipOrDrop,
            "slip outranks off table"
        );
        let off = f(&|x| x.off_table = true);
        assert_eq!(off.outcome(None), Outcome::ObjectOffTable);
        // The policy's verdict outranks slip, off table, missed grasp and timeout ...
        for below in [slip, off, missed, facts()] {
            assert_eq!(below.outcome(Some(Outcome::IkFailure)), Outcome::IkFailure);
        }
        // ... but not a collision, a stop, a fault or a success.
        let collision = f(&|x| {
            x.collision = true;
            x.protective_stop = true;
        });
        assert_eq!(
            collision.outcome(Some(Outcome::IkFailure)),
            Outcome::Collision
        );
        let stop = f(&|x| x.protective_stop = true);
        assert_eq!(stop.outcome(None), Outcome::ProtectiveStop);
        let fault = f(&|x| {
            x.physics_fault = true;
            x.collision = true;
        });
        assert_eq!(fault.outcome(None), Outcome::PhysicsFault);
        let success = f(&|x| {
            x.success = true;
            x.collision = true;
        });
        assert_eq!(success.outcome(Some(Outcome::IkFailure)), Outcome::Success);
    }

    #[test]
    fn a_record_round_trips_through_json_with_its_facts_beside_its_fields() {
        let record = EpisodeRecord {
            seed: 7,
            outcome: Outcome::SlipOrDrop,
            steps: 120,
            episode_return: 3.5,
            object_xy: [0.3, -0.1],
            collision_pair: None,
            cycle_time_s: None,
            takt_s: Some(20.0),
            facts: EpisodeFacts {
                held: true,
                lifted: true,
                ..EpisodeFacts::default()
            },
        };
        let json = serde_json::to_value(&record).unwrap();
        assert_eq!(json["held"], true);
        assert_eq!(json["success"], false);
        assert_eq!(json["outcome"], "slip_or_drop");
        let back: EpisodeRecord = serde_json::from_value(json).unwrap();
        assert_eq!(back, record);
        // A record from before the facts existed: the outcome decides `success`.
        let old: EpisodeRecord = serde_json::from_str(
            r#"{"seed":1,"outcome":"success","steps":9,"episode_return":1.0,"object_xy":[0.3,0.0]}"#,
        )
        .unwrap();
        assert!(!old.facts.success);
        assert!(old.normalized().facts.success);
    }
}
