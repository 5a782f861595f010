//! The scripted place ([`ScriptedPlace`]): the scripted grasp ([`ScriptedGrasp`], grasping
//! `task.place.grasp_height` above the cube's centre so that the cube stands out below the
//! pads), then carry → lower → release → retreat, planned once from the first observation of
//! the fixture after the lift: the place task's open-loop baseline.
//!
//! The place pose puts the cube's centre above the pocket's observed centre, its bottom
//! [`DROP_HEIGHT`] above the floor, turned to the pocket's observed yaw (of the yaws
//! `fixture_yaw + k·90°`, the one the wrist turns least to; the grasp holds the cube square to
//! the fingers). The motions are jerk-limited joint trajectories between IK targets, followed
//! as the grasp's are (feedforward plus a feedback term on the joint error).

use fairgrasp_env::cell::Cell;
use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::{Action, EnvConfig, Mount, Observation};
use fairgrasp_kinematics::ArmModel;

use fairgrasp_env::scenario::perception::ObservedObject;

use crate::correction::TaskCorrection;
use crate::grasp::{GraspJoints, GraspTarget, plan_grasp_joints};
use crate::lift::script::{BaselineConfig, Phase, ScriptedGrasp};
use crate::motion::{JointTrajectory, MotionLimits, tracking_action};
use crate::place::search::{ForceSearch, Modulation, SearchParams};
use crate::place::square::{SquareParams, Squaring};
use fairgrasp_env::config::SwitchParams;

pub use crate::place::search::DROP_HEIGHT;
/// Height of the carry above the place pose \[m\]: low, because the lower that follows is a joint
/// trajectory, whose TCP path bows away from the vertical (6 mm off over a 10 cm lower, more
/// than the pocket's clearance; about a tenth of that over 3 cm).
pub const CARRY_HEIGHT: f64 = 0.03;
/// Height of the retreat above the place pose \[m\].
pub const RETREAT_HEIGHT: f64 = 0.06;
/// Env steps the gripper is given to open before the retreat.
pub const RELEASE_STEPS: usize = 8;
/// The carry has arrived when every joint is within this of its target \[rad\]: 0.2 mm at the
/// TCP for the FR3's 0.6 m reach (the grasp's 0.01 rad is 6 mm: far more than the clearance).
pub const CARRY_TOLERANCE: f64 = 3e-4;
/// The lower moves at this fraction of the script's velocity, acceleration and jerk limits, so
/// that the feedback keeps the TCP on its path (at full speed it lags 2–3 mm, more than the
/// pocket's clearance).
pub const LOWER_SPEED: f64 = 0.25;

/// Where the place script is after the grasp.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlacePhase {
    /// The grasp script runs (approach … lift).
    Grasp,
    Carry,
    Lower,
    /// The force-guided search instead of the lower ([`crate::place::search`]).
    Search,
    /// The carry to the squaring spot beside the pocket ([`crate::place::square`]).
    SquareCarry,
    /// Squaring the cube on the table.
    Square,
    Release,
    Retreat,
    Done,
    Failed,
}

impl PlacePhase {
    fn name(self) -> &'static str {
        match self {
            PlacePhase::Grasp => "grasp",
            PlacePhase::Carry => "carry",
            PlacePhase::Lower => "lower",
            PlacePhase::Search => "search",
            PlacePhase::SquareCarry => "square_carry",
            PlacePhase::Square => "square",
            PlacePhase::Release => "release",
            PlacePhase::Retreat => "retreat",
            PlacePhase::Done => "done",
            PlacePhase::Failed => "failed",
        }
    }
}

/// The scripted place, as a [`Policy`].
pub struct ScriptedPlace {
    grasp: ScriptedGrasp,
    config: BaselineConfig,
    model: ArmModel,
    mount: Mount,
    limits: MotionLimits,
    action_scale: f64,
    /// Duration of one env step \[s\].
    step_dt: f64,
    cube_size: f64,
    grasp_height: f64,
    /// Where the cube's bottom goes, above the fixture's origin on the table top \[m\]: 0 on
    /// the pocket's floor, a cube's edge on a second cube ([`ScriptedPlace::onto`]).
    seat_height: f64,
    phase: PlacePhase,
    steps_in_phase: usize,
    /// Carry (above the pocket), place and retreat joints, once planned.
    targets: Option<GraspJoints>,
    trajectory: Option<JointTrajectory>,
    gave_up: Option<Outcome>,
    /// The force-guided search's settings, if this script searches instead of lowering.
    search_params: Option<SearchParams>,
    search: Option<ForceSearch>,
    wall_height: f64,
    /// The fixture as observed when the place was planned.
    planned_fixture: Option<ObservedObject>,
    /// Whether the place is planned for the cube where the camera sees it in the hand (the
    /// closed loop), not for where the grasp should have put it.
    reobserve: bool,
    /// A residual's correction of the search ([`crate::place::residual`]); zero otherwise.
    correction: TaskCorrection,
    /// A residual's scaling of the search's settings; none otherwise.
    modulation: Modulation,
    /// Squaring the cube on the table before the place, if this script does.
    square: Option<SquareParams>,
    squaring: Option<Squaring>,
    /// The switching search's rule (`tilt_band` \[m\] and the tilted cube's settings), if
    /// this script switches.
    switch: Option<(f64, SearchParams)>,
    /// Where the cube was first seen, `base_link` \[m\] (the squaring spot lies towards it).
    cube_start: Option<[f64; 3]>,
    /// The gripper's full squeeze per finger \[N\] (`gripper.force`), asked for again after a
    /// squaring's lowered one.
    full_squeeze: f64,
}

impl ScriptedPlace {
    /// The place script for the env `env` (its `[task.place]`).
    pub fn new(env: &EnvConfig) -> Self {
        let place = &env.task.place;
        Self::onto(env, 0.0, place.grasp_height, place.wall_height)
    }

    /// The same script setting the cube down on a seat `seat_height` \[m\] above the fixture's
    /// origin on the table top (0: the pocket's floor; the stack task's second cube: its edge),
    /// the cube held `grasp_height` \[m\] above its centre, beside walls `wall_height` \[m\]
    /// high (the search's rim; 0: none).
    pub fn onto(env: &EnvConfig, seat_height: f64, grasp_height: f64, wall_height: f64) -> Self {
        let config = BaselineConfig {
            grasp_height,
            ..BaselineConfig::default()
        };
        let grasp = ScriptedGrasp::new(env, config.clone());
        let Cell { model, mount, .. } = Cell::from_config(env);
        Self {
            limits: *grasp.limits(),
            grasp,
            config,
            model,
            mount,
            action_scale: env.arm.action_scale,
            step_dt: env.physics.dt * env.physics.substeps as f64,
            cube_size: env.scene.cube_size,
            grasp_height,
            seat_height,
            phase: PlacePhase::Grasp,
            steps_in_phase: 0,
            targets: None,
            trajectory: None,
            gave_up: None,
            search_params: None,
            search: None,
            wall_height,
            planned_fixture: None,
            correction: TaskCorrection::ZERO,
            modulation: Modulation::NONE,
            reobserve: false,
            square: None,
            squaring: None,
            switch: None,
            cube_start: None,
            full_squeeze: env.gripper.force,
        }
    }

    /// The place script that squares the cube on the table beside the pocket first
    /// ([`crate::place::square`]), then places it with its own search (`square.search`).
    pub fn with_squaring(env: &EnvConfig, square: SquareParams) -> Self {
        Self {
            square: Some(square),
            ..Self::with_search(env, square.search)
        }
    }

    /// The place script with the switching search ([`SwitchParams`]): `pose`'s settings, and
    /// `tilted`'s from a first touch that reads as a tilted cube.
    pub fn with_switch(env: &EnvConfig, switch: SwitchParams) -> Self {
        Self {
            switch: Some((switch.tilt_band, switch.tilted)),
            ..Self::with_search(env, switch.pose)
        }
    }

    /// Sets the search's settings for the episodes from the next reset on (an oracle that
    /// knows each cycle's family, [`crate::place::oracle_switch`]).
    pub fn set_search_params(&mut self, params: SearchParams) {
        self.search_params = Some(params);
    }

    /// The place script with the force-guided search ([`crate::place::search`]) in place of the
    /// open-loop lower.
    pub fn with_search(env: &EnvConfig, params: SearchParams) -> Self {
        Self::new(env).searching(params)
    }

    /// The same script with the force-guided search `params` in place of the open-loop lower.
    pub fn searching(mut self, params: SearchParams) -> Self {
        self.search_params = Some(params);
        self
    }

    /// The same script in closed loop: after the lift it looks at the cube in the hand again
    /// (the fixed camera's view, with the cell's perception error) and plans the place so that
    /// the cube it sees, not the TCP, goes over the pocket — along the pads only: across them
    /// the closing fingers have centred the cube (measured: 0.2 mm spread against 5.3 mm along
    /// the pads, docs/place.md), where the camera's own bias would be read as an offset that is
    /// not there. A cube that slid along the pads in the grasp shows; an error of the camera
    /// itself does not (it was in the grasp too).
    pub fn reobserving(mut self) -> Self {
        self.reobserve = true;
        self
    }

    /// Where the script is.
    pub fn place_phase(&self) -> PlacePhase {
        self.phase
    }

    /// The running force-guided search (None before it starts, and without one).
    pub fn search(&self) -> Option<&ForceSearch> {
        self.search.as_ref()
    }

    /// The fixture as observed when the place was planned (None before).
    pub fn planned_fixture(&self) -> Option<ObservedObject> {
        self.planned_fixture
    }

    /// The correction the search's offset gets from now on (a residual's; zero otherwise).
    pub fn set_search_correction(&mut self, c: TaskCorrection) {
        self.correction = c;
        if let Some(search) = &mut self.search {
            search.set_correction(c);
        }
    }

    /// Scales the search's settings from now on (a residual's adaptation; [`Modulation::NONE`]:
    /// as set).
    pub fn set_search_modulation(&mut self, m: Modulation) {
        self.modulation = m;
        if let Some(search) = &mut self.search {
            search.set_modulation(m);
        }
    }

    /// The correction set by [`ScriptedPlace::set_search_correction`].
    pub fn search_correction(&self) -> TaskCorrection {
        self.correction
    }

    /// The carry, place and retreat joints for the fixture in `obs`, from the arm's joints; in
    /// closed loop ([`ScriptedPlace::reobserving`]) shifted by the cube's observed offset in the
    /// hand.
    fn plan(&self, obs: &Observation) -> Option<GraspJoints> {
        let fixture = obs.fixture?;
        let up = self.mount.table_in_base.transform_vector([
            0.0,
            0.0,
            self.seat_height + 0.5 * self.cube_size + DROP_HEIGHT + self.grasp_height,
        ]);
        let mut target = GraspTarget {
            object: [0, 1, 2].map(|i| fixture.position[i] + up[i]),
            object_yaw: fixture.yaw,
            mount: self.mount,
        };
        // `plan_grasp_joints` names them pre-grasp, grasp, lift: carry, place, retreat here.
        let plan = |target: &GraspTarget| {
            plan_grasp_joints(
                &self.model,
                target,
                &obs.joints,
                CARRY_HEIGHT,
                RETREAT_HEIGHT,
            )
        };
        let first = plan(&target)?;
        if !self.reobserve {
            return Some(first);
        }
        let shift = self.in_hand_shift(obs, &first.grasp);
        target.object = [0, 1, 2].map(|i| target.object[i] - shift[i]);
        plan(&target)
    }

    /// The carry, "place" and retreat joints above the squaring spot: free table `offset` \[m\]
    /// from the pocket's observed centre, towards where the cube started, the cube turned to
    /// the pocket's yaw (so that the carry to the pocket after it does not turn it).
    fn plan_square(&self, obs: &Observation, offset: f64) -> Option<GraspJoints> {
        let fixture = obs.fixture?;
        let start = self.cube_start?;
        let z = self.mount.table_in_base.transform_vector([0.0, 0.0, 1.0]);
        let d: [f64; 3] = [0, 1, 2].map(|i| start[i] - fixture.position[i]);
        let along_z: f64 = (0..3).map(|i| d[i] * z[i]).sum();
        let flat = [0, 1, 2].map(|i| d[i] - along_z * z[i]);
        let norm = (flat[0] * flat[0] + flat[1] * flat[1] + flat[2] * flat[2]).sqrt();
        if norm < 1e-6 {
            return None;
        }
        let toward = flat.map(|v| v / norm);
        let up = 0.5 * self.cube_size + DROP_HEIGHT + self.grasp_height;
        // Towards the cube's start first, then turning away from it by 45° steps: the first
        // spot the arm reaches.
        [0.0f64, 45.0, -45.0, 90.0, -90.0, 135.0, -135.0, 180.0]
            .iter()
            .find_map(|deg| {
                let (s, c) = deg.to_radians().sin_cos();
                // `toward` turned about the table's vertical by the angle (Rodrigues; `toward`
                // is perpendicular to the vertical).
                let cross = [
                    z[1] * toward[2] - z[2] * toward[1],
                    z[2] * toward[0] - z[0] * toward[2],
                    z[0] * toward[1] - z[1] * toward[0],
                ];
                let dir: [f64; 3] = [0, 1, 2].map(|i| c * toward[i] + s * cross[i]);
                let target = GraspTarget {
                    object: [0, 1, 2].map(|i| fixture.position[i] + offset * dir[i] + up * z[i]),
                    object_yaw: fixture.yaw,
                    mount: self.mount,
                };
                plan_grasp_joints(
                    &self.model,
                    &target,
                    &obs.joints,
                    CARRY_HEIGHT,
                    RETREAT_HEIGHT,
                )
            })
    }

    /// Where the cube seen in the hand at `obs` would be, horizontally, relative to the TCP
    /// once the arm is at the place joints `place` \[rad\] (`base_link`, m; no vertical part):
    /// the offset measured along the pads (the TCP's y; the fingers close along its x) now,
    /// carried along with the gripper's turn.
    fn in_hand_shift(&self, obs: &Observation, place: &[f64; 6]) -> [f64; 3] {
        let now = self.model.fk_tcp(&obs.joints);
        let cube = obs.object_position();
        let p = now.iso.translation.vector;
        let mut in_tcp =
            now.inverse()
                .transform_vector([cube[0] - p.x, cube[1] - p.y, cube[2] - p.z]);
        in_tcp[0] = 0.0;
        let at_place = self.model.fk_tcp(place).transform_vector(in_tcp);
        let z = self.mount.table_in_base.transform_vector([0.0, 0.0, 1.0]);
        let along_z: f64 = (0..3).map(|i| at_place[i] * z[i]).sum();
        [0, 1, 2].map(|i| at_place[i] - along_z * z[i])
    }

    /// Plans the place over the pocket from where the arm is and starts the carry to it (or
    /// gives up without an IK solution).
    fn start_place(&mut self, obs: &Observation) {
        match self.plan(obs) {
            Some(t) => {
                self.targets = Some(t);
                self.planned_fixture = obs.fixture;
                self.enter(PlacePhase::Carry, obs, Some(t.pre_grasp));
            }
            None => self.give_up(),
        }
    }

    /// No IK solution for what comes next: the script stops where it is.
    fn give_up(&mut self) {
        self.phase = PlacePhase::Failed;
        self.gave_up = Some(Outcome::IkFailure);
    }

    /// The running squaring (None before it starts, and without one).
    pub fn squaring(&self) -> Option<&Squaring> {
        self.squaring.as_ref()
    }

    /// Moves to the next phase when this one is over at `obs` (the grasp held, a motion
    /// arrived, the squaring or the search done, a phase timed out).
    fn advance(&mut self, obs: &Observation) {
        if self.phase == PlacePhase::Grasp {
            match self.square {
                Some(square) => match self.plan_square(obs, square.offset) {
                    Some(t) => {
                        self.targets = Some(t);
                        self.enter(PlacePhase::SquareCarry, obs, Some(t.pre_grasp));
                    }
                    None => self.give_up(),
                },
                None => self.start_place(obs),
            }
        }
        if self.phase == PlacePhase::Square && self.squaring.as_ref().is_some_and(Squaring::done) {
            if let Some(h) = self.squaring.as_ref().and_then(Squaring::grasp_height_seen) {
                self.grasp_height = h;
            }
            self.start_place(obs);
        }
        let tolerance = match self.phase {
            PlacePhase::Carry => CARRY_TOLERANCE,
            _ => 0.01,
        };
        let arrived = self.arrived(obs, tolerance);
        match (self.phase, self.targets) {
            (PlacePhase::SquareCarry, Some(t)) if arrived => self.start_squaring(obs, &t),
            (PlacePhase::Carry, Some(t)) if arrived => match self.search_params {
                Some(params) => self.start_search(obs, params, &t),
                None => self.enter(PlacePhase::Lower, obs, Some(t.grasp)),
            },
            (PlacePhase::Search, _) if self.search.as_ref().is_some_and(ForceSearch::done) => {
                self.enter(PlacePhase::Release, obs, None)
            }
            (PlacePhase::Lower, _) if arrived => self.enter(PlacePhase::Release, obs, None),
            (PlacePhase::Release, Some(t)) if self.steps_in_phase >= RELEASE_STEPS => {
                self.enter(PlacePhase::Retreat, obs, Some(t.lift))
            }
            (PlacePhase::Retreat, _) if arrived => self.enter(PlacePhase::Done, obs, None),
            (
                PlacePhase::Carry
                | PlacePhase::SquareCarry
                | PlacePhase::Lower
                | PlacePhase::Retreat,
                _,
            ) if self.timed_out() => {
                self.phase = PlacePhase::Failed;
                self.trajectory = None;
            }
            _ => {}
        }
    }

    /// Starts squaring the cube from the carry pose above its spot (`t.pre_grasp`).
    fn start_squaring(&mut self, obs: &Observation, t: &GraspJoints) {
        if let Some(square) = self.square {
            let flat_depth = CARRY_HEIGHT + DROP_HEIGHT;
            self.squaring = Some(Squaring::new(
                square,
                t.pre_grasp,
                flat_depth,
                self.step_dt,
                self.cube_size,
            ));
        }
        self.enter(PlacePhase::Square, obs, None);
    }

    /// Starts the force search with `params` from the carry pose above the pocket.
    fn start_search(&mut self, obs: &Observation, params: SearchParams, t: &GraspJoints) {
        let mut search = ForceSearch::new(
            params,
            t.pre_grasp,
            CARRY_HEIGHT,
            self.wall_height,
            self.step_dt,
        );
        if let Some((band, tilted)) = self.switch {
            search = search.with_switch(band, tilted);
        }
        search.set_correction(self.correction);
        search.set_modulation(self.modulation);
        self.search = Some(search);
        self.enter(PlacePhase::Search, obs, None);
    }

    /// The action of the phase the script is in: the search's or the squaring's next joints,
    /// the current motion, or holding still after a failure; the gripper closed until the
    /// release.
    fn command(&mut self, obs: &Observation) -> Action {
        let gripper = match self.phase {
            PlacePhase::Release | PlacePhase::Retreat | PlacePhase::Done => -1.0,
            _ => 1.0,
        };
        let table = &self.mount.table_in_base;
        let target = match (self.phase, self.search.as_mut(), self.squaring.as_mut()) {
            (PlacePhase::Search, Some(search), _) => Some(search.step(obs, &self.model, table)),
            (PlacePhase::Square, _, Some(squaring)) => Some(squaring.step(obs, &self.model, table)),
            _ => None,
        };
        match (self.phase, target) {
            (PlacePhase::Failed, _) => Action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, gripper]),
            (_, Some(target)) => {
                let mut a = [gripper; 7];
                let q = &obs.joints;
                let joints = tracking_action(q, &target, q, 0.0, self.step_dt, self.action_scale);
                a[..6].copy_from_slice(&joints);
                Action(a)
            }
            _ => self.follow(obs, gripper),
        }
    }

    fn enter(&mut self, phase: PlacePhase, obs: &Observation, target: Option<[f64; 6]>) {
        self.phase = phase;
        self.steps_in_phase = 0;
        let limits = match phase {
            PlacePhase::Lower => MotionLimits {
                max_velocity: self.limits.max_velocity.map(|v| v * LOWER_SPEED),
                max_acceleration: self.limits.max_acceleration.map(|a| a * LOWER_SPEED),
                max_jerk: self.limits.max_jerk.map(|j| j * LOWER_SPEED),
            },
            _ => self.limits,
        };
        self.trajectory = target.and_then(|t| {
            let qd0 = std::array::from_fn(|i| {
                let v = limits.max_velocity[i];
                obs.joint_velocities[i].clamp(-v, v)
            });
            JointTrajectory::plan(&obs.joints, &qd0, &t, &limits)
                .or_else(|_| JointTrajectory::plan(&obs.joints, &[0.0; 6], &t, &limits))
                .ok()
        });
        if target.is_some() && self.trajectory.is_none() {
            self.phase = PlacePhase::Failed;
        }
    }

    /// The action following the current trajectory (holding still without one).
    fn follow(&self, obs: &Observation, gripper: f64) -> Action {
        let mut a = [0.0; 7];
        a[6] = gripper;
        if let Some(traj) = &self.trajectory {
            let t = self.steps_in_phase as f64 * self.step_dt;
            let (q_now, _, _) = traj.sample(t);
            let (q_next, _, _) = traj.sample(t + self.step_dt);
            let gain = self.config.feedback_gain;
            let (dt, scale) = (self.step_dt, self.action_scale);
            a[..6].copy_from_slice(&tracking_action(
                &q_now,
                &q_next,
                &obs.joints,
                gain,
                dt,
                scale,
            ));
        }
        Action(a)
    }

    /// The current motion is over and every joint is within `tolerance` \[rad\] of its target.
    fn arrived(&self, obs: &Observation, tolerance: f64) -> bool {
        let Some(traj) = &self.trajectory else {
            return true;
        };
        let error = traj
            .target()
            .iter()
            .zip(&obs.joints)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        self.steps_in_phase as f64 * self.step_dt >= traj.duration() && error < tolerance
    }

    fn timed_out(&self) -> bool {
        let budget = self.trajectory.as_ref().map_or(0.0, |t| t.duration()) / self.step_dt;
        self.steps_in_phase as f64 > budget + self.config.phase_slack_steps as f64
    }
}

impl Policy for ScriptedPlace {
    fn reset(&mut self, seed: u64) {
        self.grasp.reset(seed);
        self.phase = PlacePhase::Grasp;
        self.steps_in_phase = 0;
        self.targets = None;
        self.trajectory = None;
        self.gave_up = None;
        self.search = None;
        self.planned_fixture = None;
        self.correction = TaskCorrection::ZERO;
        self.modulation = Modulation::NONE;
        self.squaring = None;
        self.cube_start = None;
        self.grasp_height = self.config.grasp_height;
    }

    fn act(&mut self, obs: &Observation) -> Action {
        if self.phase == PlacePhase::Grasp && self.grasp.phase() != Phase::Hold {
            self.cube_start.get_or_insert(obs.object_position());
            return self.grasp.act(obs);
        }
        self.advance(obs);
        let action = self.command(obs);
        self.steps_in_phase += 1;
        action
    }

    fn gave_up(&self) -> Option<Outcome> {
        self.grasp.gave_up().or(self.gave_up)
    }

    fn grip_force(&self) -> Option<f64> {
        if self.square.is_none() || self.phase == PlacePhase::Grasp {
            return self.grasp.grip_force();
        }
        let lowered = self.squaring.as_ref().and_then(Squaring::squeeze);
        match (self.phase, lowered) {
            (PlacePhase::Square, Some(f)) => Some(f),
            _ => Some(self.full_squeeze),
        }
    }

    fn phase(&self) -> Option<&'static str> {
        match (self.phase, &self.search) {
            (PlacePhase::Grasp, _) => Policy::phase(&self.grasp),
            (PlacePhase::Search, Some(search)) => Some(search.stage_name()),
            (PlacePhase::Square, _) => self.squaring.as_ref().map(Squaring::stage_name),
            (p, _) => Some(p.name()),
        }
    }
}
