//! Scene diagnostics (`fairgrasp scene`): every contact right after a reset with its verdict
//! (what counts as a collision, what is ignored), the arm's capsules that overlap at the home
//! pose, and which of many reset seeds start broken.
//!
//! The verdicts are the environment's own ([`crate::sim::contacts`]); the capsule check is the
//! kinematics library's (`ArmModel::self_collisions`, the one scenario sampling uses).

use std::fmt;

use fairgrasp_kinematics::ArmModel;
use fairgrasp_kinematics::collision::segment_distance;
use serde::{Serialize, Serializer};

use crate::config::EnvConfig;
use crate::env::{Action, EnvError, TaskEnv};
use crate::scenario::Scenario;
use crate::sim::contacts::{PairKind, TouchingPair};

/// What a contact right after a reset means.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactVerdict {
    /// A pair the environment counts as a collision (it would end the episode).
    Collision,
    /// The object touches the robot at spawn (a broken start, though not a collision).
    ObjectTouchesRobot,
    /// The object resting on the table.
    RestingContact,
    /// A robot pair the collision filter ignores.
    Ignored,
    /// Any other pair of scene parts.
    Scene,
}

impl ContactVerdict {
    /// The verdict on a touching pair.
    pub fn of(p: &TouchingPair) -> Self {
        match p.kind {
            PairKind::Collision => Self::Collision,
            PairKind::Object if p.a.is_robot() || p.b.is_robot() => Self::ObjectTouchesRobot,
            PairKind::Object => Self::RestingContact,
            PairKind::Ignored => Self::Ignored,
            PairKind::Scene => Self::Scene,
        }
    }

    /// Does this contact make the start broken?
    pub fn is_bad(self) -> bool {
        matches!(self, Self::Collision | Self::ObjectTouchesRobot)
    }
}

impl fmt::Display for ContactVerdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Collision => "COLLISION (counted)",
            Self::ObjectTouchesRobot => "object touches the robot at spawn",
            Self::RestingContact => "resting contact (not a collision)",
            Self::Ignored => "ignored pair",
            Self::Scene => "scene contact",
        })
    }
}

impl Serialize for ContactVerdict {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One contact after the reset and one step holding still.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contact {
    /// Scene part names.
    pub a: String,
    pub b: String,
    /// Signed distance \[m\] (negative: penetrating).
    pub distance_m: f64,
    pub verdict: ContactVerdict,
}

/// Two capsules of the kinematic model that overlap at a joint configuration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CapsuleOverlap {
    pub a: &'static str,
    pub b: &'static str,
    /// Penetration depth \[m\] (positive).
    pub overlap_m: f64,
    /// Never checked (adjacent links, the model's ignored pairs, the gripper's own parts).
    pub ignored: bool,
}

/// Everything `fairgrasp scene` reports about a config.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneDiagnosis {
    /// The reset seed shown in detail.
    pub seed: u64,
    /// Why the scenario of `seed` is refused at reset (then the config's own, unchecked cube
    /// position is shown).
    pub refused: Option<String>,
    /// Object position after the reset and one step, in `base_link` \[m\].
    pub object_xyz_base: [f64; 3],
    /// How far the object moved from its spawn on the table plane \[m\] (a spawn overlap pushes
    /// it away).
    pub object_pushed_m: f64,
    /// The gripper's widest opening between the pads \[m\].
    pub max_opening_m: f64,
    pub contacts: Vec<Contact>,
    /// Capsule pairs overlapping at the config's home joints.
    pub capsule_overlaps_at_home: Vec<CapsuleOverlap>,
    /// Seeds `0..seeds_checked` were also reset and checked.
    pub seeds_checked: u64,
    /// Those of them refused or starting with a bad contact.
    pub bad_starts: Vec<u64>,
}

impl SceneDiagnosis {
    /// Is the start of `seed` broken (refused, or a bad contact)?
    pub fn start_is_bad(&self) -> bool {
        self.refused.is_some() || self.contacts.iter().any(|c| c.verdict.is_bad())
    }
}

/// The scenario of `seed`, or the config's unchecked one and the reason it was refused.
fn scenario_or_refusal(env: &TaskEnv, seed: u64) -> (Scenario, Option<String>) {
    match Scenario::sample_in(env.cell(), env.config(), seed) {
        Ok(s) => (s, None),
        Err(e) => (Scenario::unchecked(env.config(), seed), Some(e.to_string())),
    }
}

/// The touching pairs after resetting to `scenario` and one step that holds the arm still, and
/// how far the object is from its spawn on the table plane \[m\].
fn contacts_at_start(
    env: &mut TaskEnv,
    scenario: &Scenario,
) -> Result<(Vec<TouchingPair>, f64), EnvError> {
    env.reset_to(scenario);
    env.step(&Action::hold_open())?;
    let after = env.object_in_base().xyz();
    let [x, y] = scenario.object_xy;
    Ok((env.touching_pairs(), (after[0] - x).hypot(after[1] - y)))
}

/// Capsule pairs of `model` overlapping at joints `q` \[rad\]: the counted ones from the
/// kinematics' self-collision check, then the ignored ones it skips (measured here to show what
/// the filter hides).
pub fn capsule_overlaps(model: &ArmModel, q: &[f64; 6]) -> Vec<CapsuleOverlap> {
    let mut out: Vec<CapsuleOverlap> = model
        .self_collisions(q, 0.0)
        .into_iter()
        .map(|(a, b, clearance)| CapsuleOverlap {
            a,
            b,
            overlap_m: -clearance,
            ignored: false,
        })
        .collect();
    let capsules = model.placed_capsules(q);
    for (i, c) in capsules.iter().enumerate() {
        for d in capsules[i + 1..]
            .iter()
            .filter(|d| model.collision_ignored(c.name, d.name))
        {
            let clearance = segment_distance(c.a, c.b, d.a, d.b) - c.radius - d.radius;
            if clearance < 0.0 {
                out.push(CapsuleOverlap {
                    a: c.name,
                    b: d.name,
                    overlap_m: -clearance,
                    ignored: true,
                });
            }
        }
    }
    out
}

/// Resets `config`'s environment to the scenario of `seed` and reports its contacts, the
/// capsule overlaps at home, and which of the seeds `0..seeds` start broken.
pub fn diagnose_scene(
    config: &EnvConfig,
    seed: u64,
    seeds: u64,
) -> Result<SceneDiagnosis, EnvError> {
    let mut env = TaskEnv::new(config.clone())?;
    let (scenario, refused) = scenario_or_refusal(&env, seed);
    let (pairs, object_pushed_m) = contacts_at_start(&mut env, &scenario)?;
    let object_xyz_base = env.object_in_base().xyz();
    let model = env.model().clone();
    let contacts = pairs
        .iter()
        .map(|p| Contact {
            a: p.a.name(&model).to_string(),
            b: p.b.name(&model).to_string(),
            distance_m: p.distance,
            verdict: ContactVerdict::of(p),
        })
        .collect();
    let mut bad_starts = Vec::new();
    for s in 0..seeds {
        let (scenario, refused) = scenario_or_refusal(&env, s);
        let bad = refused.is_some()
            || contacts_at_start(&mut env, &scenario)?
                .0
                .iter()
                .any(|p| ContactVerdict::of(p).is_bad());
        if bad {
            bad_starts.push(s);
        }
    }
    Ok(SceneDiagnosis {
        seed,
        refused,
        object_xyz_base,
        object_pushed_m,
        max_opening_m: model.gripper.opening(0.0),
        contacts,
        capsule_overlaps_at_home: capsule_overlaps(&model, &config.arm.home_joints),
        seeds_checked: seeds,
        bad_starts,
    })
}
