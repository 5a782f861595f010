//! The scripted grasp baseline: approach → descend → close → lift → hold.
//!
//! Each motion phase follows a Ruckig trajectory between IK joint targets; each env step emits
//! the joint velocity that moves along the reference over the coming step plus a small feedback
//! term, `q̇ = (q_ref(t+Δ) − q_ref(t))/Δ + K·(q_ref(t) − q)`, scaled into the action range.
//!
//! A residual may correct the script ([`crate::lift::residual`]): the reference then follows a
//! task-space [`TaskCorrection`] (`q_ref + J⁺·c`, so the feedback term holds the correction
//! instead of erasing it), a phase is complete when the joints reach the *corrected* target, and
//! [`CloseTiming`] may close the gripper during the descent or hold it open a little longer.
//! With no correction and [`CloseTiming::Script`] the script is exactly the open-loop baseline.

use fairgrasp_env::cell::Cell;
use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::{Action, EnvConfig, Mount, Observation};
use fairgrasp_kinematics::ArmModel;
use serde::Serialize;

pub use crate::correction::CloseTiming;
use crate::correction::{TaskCorrection, corrected, joint_offset};
pub use crate::grasp::PlannedObject;
use crate::grasp::{GraspJoints, GraspTarget, plan_grasp_joints};
use crate::motion::{JointTrajectory, MotionLimits, tracking_action};
pub use crate::phase::Phase;

/// Settings of the scripted grasp.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BaselineConfig {
    /// Pre-grasp height above the object centre \[m\].
    pub pre_grasp_height: f64,
    /// Lift above the grasp \[m\].
    pub lift_height: f64,
    /// Fraction of the action's velocity range the trajectories may use (the rest is headroom
    /// for the feedback term).
    pub velocity_fraction: f64,
    /// Trajectory acceleration limit \[rad/s²\] (the env's arm limit is 10).
    pub max_acceleration: f64,
    /// Trajectory jerk limit \[rad/s³\].
    pub max_jerk: f64,
    /// Feedback gain on the joint error \[1/s\].
    pub feedback_gain: f64,
    /// Env steps the gripper closes before lifting.
    pub close_steps: usize,
    /// Extra env steps a motion phase may take beyond its trajectory before it times out.
    pub phase_slack_steps: usize,
    /// Env steps a residual may hold the gripper open after the descent arrived
    /// ([`CloseTiming::Wait`]).
    pub max_close_delay_steps: usize,
    /// Where the TCP grasps the cube: this far above its centre along the vertical \[m\] (0: at
    /// the centre; the place task grasps higher so that the cube stands out below the pads).
    pub grasp_height: f64,
}

impl Default for BaselineConfig {
    fn default() -> Self {
        Self {
            pre_grasp_height: 0.10,
            lift_height: 0.10,
            velocity_fraction: 0.8,
            max_acceleration: 2.0,
            max_jerk: 20.0,
            feedback_gain: 4.0,
            close_steps: 8,
            phase_slack_steps: 24,
            max_close_delay_steps: 12,
            grasp_height: 0.0,
        }
    }
}

/// Distances \[m\] across the table, nearest first, at which [`ScriptedGrasp`] looks for a
/// graspable pose when the observed cube admits none (8 directions each).
pub const NEAREST_GRASP_SEARCH: [f64; 5] = [0.005, 0.01, 0.015, 0.02, 0.03];

/// The scripted top-down grasp, as a [`Policy`].
pub struct ScriptedGrasp {
    config: BaselineConfig,
    model: ArmModel,
    action_scale: f64,
    /// Duration of one env step \[s\].
    step_dt: f64,
    limits: MotionLimits,
    /// The arm's mount (base and table frame), known to the script like a real cell's layout.
    mount: Mount,
    phase: Phase,
    steps_in_phase: usize,
    targets: Option<GraspJoints>,
    trajectory: Option<JointTrajectory>,
    gave_up: Option<Outcome>,
    planned_on: Option<PlannedObject>,
    /// The correction the reference follows from this step on.
    correction: TaskCorrection,
    /// The correction the previous step's reference used.
    applied: TaskCorrection,
    close_timing: CloseTiming,
    /// Steps the close has been delayed in this descent.
    close_delay: usize,
}

impl ScriptedGrasp {
    /// A baseline for the environment configured by `env`.
    pub fn new(env: &EnvConfig, config: BaselineConfig) -> Self {
        let Cell { model, mount, .. } = Cell::from_config(env);
        let v = env.arm.action_scale * config.velocity_fraction;
        let limits = MotionLimits {
            max_velocity: model.joints.map(|j| v.min(j.max_velocity)),
            max_acceleration: [config.max_acceleration.min(env.arm.max_acceleration); 6],
            max_jerk: [config.max_jerk; 6],
        };
        Self {
            step_dt: env.physics.dt * env.physics.substeps as f64,
            action_scale: env.arm.action_scale,
            mount,
            config,
            model,
            limits,
            phase: Phase::Plan,
            steps_in_phase: 0,
            targets: None,
            trajectory: None,
            gave_up: None,
            planned_on: None,
            correction: TaskCorrection::ZERO,
            applied: TaskCorrection::ZERO,
            close_timing: CloseTiming::Script,
            close_delay: 0,
        }
    }

    /// The object pose the current plan was made on (None before planning).
    pub fn planned_on(&self) -> Option<PlannedObject> {
        self.planned_on
    }

    /// The correction the reference follows from the next step on.
    pub fn set_correction(&mut self, c: TaskCorrection) {
        self.correction = c;
    }

    /// The correction in force.
    pub fn correction(&self) -> TaskCorrection {
        self.correction
    }

    /// When the gripper closes, for the next step.
    pub fn set_close_timing(&mut self, timing: CloseTiming) {
        self.close_timing = timing;
    }

    /// `q` with the correction `c` added (Newton steps through the Jacobian).
    fn with(&self, q: &[f64; 6], c: &TaskCorrection) -> [f64; 6] {
        corrected(&self.model, &self.mount.table_in_base, q, c)
    }

    /// The measured joints with the applied correction taken out: where the uncorrected
    /// reference is, for planning a trajectory that starts where the arm is.
    fn uncorrected(&self, q: &[f64; 6]) -> [f64; 6] {
        let dq = joint_offset(&self.model, &self.mount.table_in_base, q, &self.applied);
        std::array::from_fn(|i| q[i] - dq[i])
    }

    /// The current phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// The joint targets of this episode's grasp, once planned.
    pub fn targets(&self) -> Option<&GraspJoints> {
        self.targets.as_ref()
    }

    /// The trajectory limits in use.
    pub fn limits(&self) -> &MotionLimits {
        &self.limits
    }

    /// The current phase's trajectory, if it has one.
    pub fn trajectory(&self) -> Option<&JointTrajectory> {
        self.trajectory.as_ref()
    }

    /// The grasp's joint targets for the object in `obs`, from its joints. Remembers the object
    /// pose it was made on ([`ScriptedGrasp::planned_on`]) when it succeeds.
    ///
    /// If the observed cube admits no grasp (an observation error can put it beyond reach or
    /// against the base), the nearest pose that does is planned for instead: the observed one
    /// moved up to [`NEAREST_GRASP_SEARCH`] across the table, nearest first. A cube that is
    /// really there lies within the observation's error of such a pose.
    fn plan(&mut self, obs: &Observation) -> Option<GraspJoints> {
        let observed = obs.object_position();
        let shifts = std::iter::once([0.0, 0.0]).chain(NEAREST_GRASP_SEARCH.iter().flat_map(|r| {
            (0..8).map(move |k| {
                let a = k as f64 * std::f64::consts::FRAC_PI_4;
                [r * a.cos(), r * a.sin()]
            })
        }));
        for [dx, dy] in shifts {
            let d = self.mount.table_in_base.transform_vector([dx, dy, 0.0]);
            let position = [0, 1, 2].map(|i| observed[i] + d[i]);
            if let Some(joints) = self.plan_joints(obs, position) {
                self.planned_on = Some(PlannedObject {
                    position,
                    yaw: obs.object_yaw,
                });
                return Some(joints);
            }
        }
        None
    }

    fn plan_joints(&self, obs: &Observation, object: [f64; 3]) -> Option<GraspJoints> {
        let c = &self.config;
        let up = (self.mount.table_in_base).transform_vector([0.0, 0.0, c.grasp_height]);
        let target = GraspTarget {
            object: [0, 1, 2].map(|i| object[i] + up[i]),
            object_yaw: obs.object_yaw,
            mount: self.mount,
        };
        plan_grasp_joints(
            &self.model,
            &target,
            &obs.joints,
            c.pre_grasp_height,
            c.lift_height,
        )
    }

    /// Plans the grasp again for the object in `obs` and heads for its pre-grasp from where the
    /// arm is, moving as it moves (the approach starts over: above the object, then down).
    /// Returns false, keeping the current plan, if the new object admits no grasp.
    pub fn replan(&mut self, obs: &Observation) -> bool {
        let Some(t) = self.plan(obs) else {
            return false;
        };
        self.targets = Some(t);
        // Ruckig needs a start within its limits; the measured velocity may overshoot them a bit.
        let qd0 = std::array::from_fn(|i| {
            let v = self.limits.max_velocity[i];
            obs.joint_velocities[i].clamp(-v, v)
        });
        self.phase = Phase::Approach;
        self.steps_in_phase = 0;
        let start = self.uncorrected(&obs.joints);
        self.trajectory = JointTrajectory::plan(&start, &qd0, &t.pre_grasp, &self.limits)
            .or_else(|_| JointTrajectory::plan(&start, &[0.0; 6], &t.pre_grasp, &self.limits))
            .ok();
        if self.trajectory.is_none() {
            self.fail(Outcome::Timeout);
        }
        true
    }

    fn enter(&mut self, phase: Phase, obs: &Observation, target: Option<[f64; 6]>) {
        self.phase = phase;
        self.steps_in_phase = 0;
        self.close_delay = 0;
        let start = self.uncorrected(&obs.joints);
        self.trajectory =
            target.and_then(|t| JointTrajectory::plan(&start, &[0.0; 6], &t, &self.limits).ok());
        if target.is_some() && self.trajectory.is_none() {
            self.fail(Outcome::Timeout);
        }
    }

    fn fail(&mut self, reason: Outcome) {
        self.phase = Phase::Failed;
        self.gave_up = Some(reason);
        self.trajectory = None;
    }

    /// Velocity action following the current trajectory, corrected, from the measured joints.
    /// Without a trajectory (closing, holding) the arm stays, but follows a changed correction.
    fn follow(&self, obs: &Observation, gripper: f64) -> Action {
        let mut a = [0.0; 7];
        a[6] = gripper;
        let Some(traj) = &self.trajectory else {
            if self.correction != self.applied {
                let before = self.with(&obs.joints, &self.applied);
                let after = self.with(&obs.joints, &self.correction);
                for i in 0..6 {
                    let v = (after[i] - before[i]) / self.step_dt;
                    a[i] = (v / self.action_scale).clamp(-1.0, 1.0);
                }
            }
            return Action(a);
        };
        let t = self.steps_in_phase as f64 * self.step_dt;
        let q_now = self.with(&traj.sample(t).0, &self.applied);
        let q_next = self.with(&traj.sample(t + self.step_dt).0, &self.correction);
        let gain = self.config.feedback_gain;
        let joints = tracking_action(
            &q_now,
            &q_next,
            &obs.joints,
            gain,
            self.step_dt,
            self.action_scale,
        );
        a[..6].copy_from_slice(&joints);
        Action(a)
    }

    /// Has the current motion phase finished (trajectory over, joints there)?
    fn arrived(&self, obs: &Observation) -> bool {
        let Some(traj) = &self.trajectory else {
            return true;
        };
        let elapsed = self.steps_in_phase as f64 * self.step_dt;
        let error = self
            .with(&traj.target(), &self.correction)
            .iter()
            .zip(&obs.joints)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        elapsed >= traj.duration() && error < 0.01
    }

    fn timed_out(&self) -> bool {
        let budget = self.trajectory.as_ref().map_or(0.0, |t| t.duration()) / self.step_dt;
        self.steps_in_phase as f64 > budget + self.config.phase_slack_steps as f64
    }
}

impl Policy for ScriptedGrasp {
    fn reset(&mut self, _seed: u64) {
        self.phase = Phase::Plan;
        self.steps_in_phase = 0;
        self.targets = None;
        self.trajectory = None;
        self.gave_up = None;
        self.planned_on = None;
        self.correction = TaskCorrection::ZERO;
        self.applied = TaskCorrection::ZERO;
        self.close_timing = CloseTiming::Script;
        self.close_delay = 0;
    }

    fn act(&mut self, obs: &Observation) -> Action {
        if self.phase == Phase::Plan {
            match self.plan(obs) {
                Some(t) => {
                    self.targets = Some(t);
                    self.enter(Phase::Approach, obs, Some(t.pre_grasp));
                }
                None => self.fail(Outcome::IkFailure),
            }
        }
        let targets = self.targets;
        let mut advance = self.arrived(obs);
        let mut waiting = false;
        if self.phase == Phase::Descend {
            match self.close_timing {
                CloseTiming::Script => {}
                CloseTiming::Now => advance = true,
                CloseTiming::Wait => {
                    if advance && self.close_delay < self.config.max_close_delay_steps {
                        self.close_delay += 1;
                        advance = false;
                        waiting = true;
                    }
                }
            }
        }
        let (next, gripper) = match (self.phase, targets) {
            (Phase::Approach, Some(t)) if advance => (Some((Phase::Descend, Some(t.grasp))), -1.0),
            (Phase::Descend, Some(_)) if advance => (Some((Phase::Close, None)), 1.0),
            (Phase::Close, Some(t)) if self.steps_in_phase >= self.config.close_steps => {
                (Some((Phase::Lift, Some(t.lift))), 1.0)
            }
            (Phase::Lift, Some(_)) if advance => (Some((Phase::Hold, None)), 1.0),
            (Phase::Approach | Phase::Descend, _) => (None, -1.0),
            (Phase::Close | Phase::Lift | Phase::Hold, _) => (None, 1.0),
            (Phase::Plan | Phase::Failed, _) => (None, -1.0),
        };
        if let Some((phase, target)) = next {
            self.enter(phase, obs, target);
        } else if !waiting
            && matches!(self.phase, Phase::Approach | Phase::Descend | Phase::Lift)
            && self.timed_out()
        {
            self.fail(Outcome::Timeout);
        }
        let action = match self.phase {
            Phase::Failed | Phase::Plan => Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, gripper]),
            _ => self.follow(obs, gripper),
        };
        self.applied = self.correction;
        self.steps_in_phase += 1;
        action
    }

    fn gave_up(&self) -> Option<Outcome> {
        // A timed-out phase is reported by the episode's own end (timeout); only IK is ours.
        self.gave_up.filter(|o| *o == Outcome::IkFailure)
    }

    fn phase(&self) -> Option<&'static str> {
        Some(self.phase.name())
    }
}
