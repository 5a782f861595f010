//! Two controls for the scripted grasp ([`ScriptedGrasp`], which plans once from its first
//! observation):
//!
//! - the **closed-loop script** re-reads the cube every step and plans again (from where the arm
//!   is, through the pre-grasp) when its estimate moves more than
//!   [`ClosedLoopConfig::replan_distance`] or turns more than [`ClosedLoopConfig::replan_yaw`]
//!   from the one its plan was made on, during the approach and the descent; after a missed
//!   grasp (the gripper closed without both pads on the cube) it opens, rises to the pre-grasp
//!   of a new plan and descends again, [`ClosedLoopConfig::retries`] times at most; when the
//!   preset has a wrist camera and it sees the cube, its (exact) view is the estimate;
//! - the **oracle** is the same closed loop fed the cube's true pose
//!   ([`Policy::observe_truth`]) instead of the observed one: the ceiling.

use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::scenario::perception::ObservedObject;
use fairgrasp_env::{Action, EnvConfig, Observation};
use fairgrasp_kinematics::analytic_ik::wrap_pi;
use serde::Serialize;

use crate::lift::script::{BaselineConfig, Phase, ScriptedGrasp};

/// Settings of the closed-loop script.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosedLoopConfig {
    /// Plan again when the estimated cube centre is this far \[m\] from the planned-on one
    /// (1 cm: well above a still cube's jitter, 0 without noise; well below the 1.75 cm the open
    /// fingers tolerate across the cube).
    pub replan_distance: f64,
    /// Plan again when the estimated yaw (modulo 90°) turns this much \[rad\] (5°).
    pub replan_yaw: f64,
    /// Env steps the gripper is given to open after a missed grasp before the arm moves.
    pub open_steps: usize,
    /// Missed grasps retried per episode.
    pub retries: usize,
}

impl Default for ClosedLoopConfig {
    fn default() -> Self {
        Self {
            replan_distance: 0.01,
            replan_yaw: 5f64.to_radians(),
            open_steps: 6,
            retries: 1,
        }
    }
}

/// Where the cube estimate comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum CubeSource {
    /// The observation (the closed-loop script).
    Observed,
    /// The env's truth (the oracle).
    Truth,
}

/// The scripted grasp closed around the cube estimate, as a [`Policy`].
pub struct ClosedLoopGrasp {
    script: ScriptedGrasp,
    config: ClosedLoopConfig,
    source: CubeSource,
    truth: Option<ObservedObject>,
    /// The cube estimate (centre in `base_link` \[m\], yaw \[rad\]) the current plan was made on.
    planned_on: Option<([f64; 3], f64)>,
    retries_left: usize,
    /// Env steps left of re-opening the gripper before the retry's plan.
    opening: usize,
    replans: usize,
}

impl ClosedLoopGrasp {
    /// The closed-loop script (`CubeSource::Observed`) or the oracle (`CubeSource::Truth`).
    pub fn new(
        env: &EnvConfig,
        baseline: BaselineConfig,
        config: ClosedLoopConfig,
        source: CubeSource,
    ) -> Self {
        Self {
            script: ScriptedGrasp::new(env, baseline),
            retries_left: config.retries,
            config,
            source,
            truth: None,
            planned_on: None,
            opening: 0,
            replans: 0,
        }
    }

    /// The oracle: the closed loop on the true cube pose.
    pub fn oracle(env: &EnvConfig) -> Self {
        let c = ClosedLoopConfig::default();
        Self::new(env, BaselineConfig::default(), c, CubeSource::Truth)
    }

    /// The closed-loop script on the observed cube.
    pub fn observed(env: &EnvConfig) -> Self {
        let c = ClosedLoopConfig::default();
        Self::new(env, BaselineConfig::default(), c, CubeSource::Observed)
    }

    /// The script's phase.
    pub fn phase(&self) -> Phase {
        self.script.phase()
    }

    /// Missed grasps retried in this episode.
    pub fn retried(&self) -> usize {
        self.config.retries - self.retries_left
    }

    /// Plans made after the first one in this episode (re-plans and retries).
    pub fn replans(&self) -> usize {
        self.replans
    }

    /// The observation with the cube replaced by the estimate this script works on: the truth
    /// for the oracle; for the closed loop the wrist camera's view when it has one (it is
    /// exact), else the observed cube.
    fn estimate(&self, obs: &Observation) -> Observation {
        let replaced = |t: &ObservedObject| Observation {
            object_rel_tcp: [0, 1, 2].map(|i| t.position[i] - obs.tcp_position[i]),
            object_yaw: t.yaw,
            ..*obs
        };
        match (self.source, self.truth, obs.wrist_camera) {
            (CubeSource::Truth, Some(t), _) => replaced(&t),
            (CubeSource::Observed, _, Some(w)) => replaced(&w),
            _ => *obs,
        }
    }

    fn moved(&self, obs: &Observation) -> bool {
        let Some((p, yaw)) = self.planned_on else {
            return false;
        };
        let q = obs.object_position();
        let d = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2)).sqrt();
        // A cube's yaw means something modulo 90°.
        let turn = wrap_pi(4.0 * (obs.object_yaw - yaw)).abs() / 4.0;
        d > self.config.replan_distance || turn > self.config.replan_yaw
    }

    fn replan(&mut self, obs: &Observation) {
        if self.script.replan(obs) {
            self.planned_on = Some((obs.object_position(), obs.object_yaw));
            self.replans += 1;
        }
    }
}

impl Policy for ClosedLoopGrasp {
    fn reset(&mut self, seed: u64) {
        self.script.reset(seed);
        self.truth = None;
        self.planned_on = None;
        self.retries_left = self.config.retries;
        self.opening = 0;
        self.replans = 0;
    }

    fn observe_truth(&mut self, truth: &ObservedObject) {
        self.truth = Some(*truth);
    }

    fn act(&mut self, obs: &Observation) -> Action {
        let obs = self.estimate(obs);
        if self.opening > 0 {
            self.opening -= 1;
            if self.opening == 0 {
                self.replan(&obs);
            }
            return Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]);
        }
        let phase = self.script.phase();
        if matches!(phase, Phase::Approach | Phase::Descend) && self.moved(&obs) {
            self.replan(&obs);
        }
        let before = self.script.phase();
        let action = self.script.act(&obs);
        if self.planned_on.is_none() && self.script.targets().is_some() {
            self.planned_on = Some((obs.object_position(), obs.object_yaw));
        }
        // The close is over and the script would lift: a miss if the pads are not both on it.
        let missed = before == Phase::Close
            && self.script.phase() == Phase::Lift
            && !(obs.pad_contact[0] && obs.pad_contact[1]);
        if missed && self.retries_left > 0 {
            self.retries_left -= 1;
            self.opening = self.config.open_steps.max(1);
            return Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]);
        }
        action
    }

    fn gave_up(&self) -> Option<Outcome> {
        self.script.gave_up()
    }

    /// The script's phase, or `reopen` while the gripper opens for a retry.
    fn phase(&self) -> Option<&'static str> {
        Some(if self.opening > 0 {
            "reopen"
        } else {
            self.script.phase().name()
        })
    }
}
