//! The interface a residual policy corrects the script through (`agent.action_space = "tcp"` in
//! residual mode), and the hand-written oracle residual that proves the interface can express
//! the fix.
//!
//! Each step the policy's action (7 values in [-1, 1]) is read as:
//! - entries 0–3: a command for the task-space [`TaskCorrection`] (TCP offset along the table
//!   frame's x, y, z, and yaw about its vertical; × [`CorrectionLimits::max_offset`] (x, y),
//!   [`CorrectionLimits::max_height`] (z) and
//!   [`CorrectionLimits::max_yaw`]). The correction follows the command through a first-order
//!   filter with a rate limit ([`CorrectionLimits::follow`]): it persists between steps, and
//!   per-step exploration noise becomes a slowly varying, bounded offset of the grasp
//!   (time-correlated exploration). It is frozen once the gripper closes: it places the grasp,
//!   the script lifts from there.
//! - entry 4: the squeeze, only when the residual has it ([`ResidualScript::squeezing`],
//!   `agent.squeeze = true`; unused otherwise): through the same filter, the grip force per
//!   finger is `gripper.force + s·`[`CorrectionLimits::max_squeeze`] for a filtered command
//!   `s ≥ 0`, down to [`MIN_GRIP_FORCE`] at `s = −1` ([`ResidualScript::grip_force`]). It is
//!   not frozen: the policy may squeeze harder as it lifts. The policy does not see it.
//! - entry 5: unused.
//! - entry 6: the close's timing, through the same filter: above 0.5 close now (during the
//!   descent), below −0.5 hold open a little longer ([`CloseTiming`]), between them the
//!   script's timing. (Unfiltered, σ = 0.3 exploration noise alone would close early on one
//!   descent step in ten.)
//!
//! The script's joint reference follows the correction ([`ScriptedGrasp::set_correction`]).
//! An all-zero action is the open-loop script exactly.
//!
//! The policy sees, besides the observation, [`FEATURE_DIM`] values ([`FEATURE_NAMES`]): the
//! script's phase, how far the observed cube now is from the one the plan was made on (a push
//! shows here), the correction so far, the filtered close command, and, when the wrist camera
//! sees the cube ([`Observation::wrist_camera`]), how far its view is from the planned-on cube
//! (all zero without a wrist view).

use fairgrasp_env::cell::Cell;
use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::scenario::perception::ObservedObject;
use fairgrasp_env::{Action, EnvConfig, Mount, Observation};
use std::f64::consts::FRAC_PI_2;

use crate::correction::{CorrectionLimits, TaskCorrection};
use crate::lift::script::{BaselineConfig, CloseTiming, Phase, ScriptedGrasp};
pub use crate::task_residual::FEATURE_DIM;
use crate::task_residual::{OUTPUT_DIM, TaskResidual};

/// Names of the added values, in order.
pub const FEATURE_NAMES: [&str; FEATURE_DIM] = [
    "phase_approach",
    "phase_descend",
    "phase_close",
    "phase_lift",
    "phase_hold",
    "cube_moved_x",
    "cube_moved_y",
    "cube_moved_z",
    "cube_turned",
    "correction_x",
    "correction_y",
    "correction_z",
    "correction_yaw",
    "close_signal",
    "wrist_valid",
    "wrist_offset_x",
    "wrist_offset_y",
    "wrist_offset_z",
    "wrist_turn",
];

/// Above this the gripper entry closes now; below its negative it waits.
pub const CLOSE_THRESHOLD: f64 = 0.5;

/// The weakest squeeze the residual may ask for, per finger \[N\].
pub const MIN_GRIP_FORCE: f64 = 1.0;

/// The squeeze a residual commands, when it has one.
#[derive(Clone, Copy, Debug)]
struct Squeeze {
    /// The env's `gripper.force` \[N\].
    base: f64,
    /// The filtered squeeze command (in [-1, 1]).
    signal: f64,
}

/// `angle` wrapped into [−45°, 45°): a cube's yaw means nothing more.
pub fn wrap_quarter(angle: f64) -> f64 {
    angle - FRAC_PI_2 * (angle / FRAC_PI_2).round()
}

/// The script under a residual's correction.
pub struct ResidualScript {
    script: ScriptedGrasp,
    limits: CorrectionLimits,
    mount: Mount,
    /// Duration of one env step \[s\].
    step_dt: f64,
    /// The filtered close-timing command.
    close_signal: f64,
    /// The squeeze, if this residual has it.
    squeeze: Option<Squeeze>,
}

impl ResidualScript {
    /// The default script and limits for the env configured by `env`.
    pub fn new(env: &EnvConfig) -> Self {
        Self::with(env, BaselineConfig::default(), CorrectionLimits::default())
    }

    pub fn with(env: &EnvConfig, baseline: BaselineConfig, limits: CorrectionLimits) -> Self {
        Self {
            script: ScriptedGrasp::new(env, baseline),
            limits,
            mount: Cell::from_config(env).mount,
            step_dt: env.physics.dt * env.physics.substeps as f64,
            close_signal: 0.0,
            squeeze: None,
        }
    }

    /// The same script with the squeeze: action entry 4 commands the grip force (module doc).
    pub fn squeezing(mut self, env: &EnvConfig) -> Self {
        self.squeeze = Some(Squeeze {
            base: env.gripper.force,
            signal: 0.0,
        });
        self
    }

    /// The script inside.
    pub fn script(&self) -> &ScriptedGrasp {
        &self.script
    }

    pub fn limits(&self) -> &CorrectionLimits {
        &self.limits
    }

    /// Duration of one env step \[s\].
    pub fn step_dt(&self) -> f64 {
        self.step_dt
    }

    /// Whether the correction may still change (the gripper has not closed).
    pub fn correcting(&self) -> bool {
        matches!(
            self.script.phase(),
            Phase::Plan | Phase::Approach | Phase::Descend
        )
    }

    /// The filtered close-timing command (in [-1, 1]).
    pub fn close_signal(&self) -> f64 {
        self.close_signal
    }
}

impl TaskResidual for ResidualScript {
    fn reset(&mut self, seed: u64) {
        self.script.reset(seed);
        self.close_signal = 0.0;
        if let Some(s) = &mut self.squeeze {
            s.signal = 0.0;
        }
    }

    /// The env action for the policy's `action` at `obs` (see the module doc).
    fn act(&mut self, obs: &Observation, action: &[f64; OUTPUT_DIM]) -> Action {
        if self.correcting() {
            let c = self
                .limits
                .follow(&self.script.correction(), action, self.step_dt);
            self.script.set_correction(c);
        }
        let alpha = self.limits.gain(self.step_dt);
        self.close_signal += (action[6].clamp(-1.0, 1.0) - self.close_signal) * alpha;
        if let Some(s) = &mut self.squeeze {
            s.signal += (action[4].clamp(-1.0, 1.0) - s.signal) * alpha;
        }
        let timing = if self.close_signal > CLOSE_THRESHOLD {
            CloseTiming::Now
        } else if self.close_signal < -CLOSE_THRESHOLD {
            CloseTiming::Wait
        } else {
            CloseTiming::Script
        };
        self.script.set_close_timing(timing);
        self.script.act(obs)
    }

    /// Writes the [`FEATURE_NAMES`] values for the next decision at `obs` into `out`.
    fn write_features(&self, obs: &Observation, out: &mut [f64; FEATURE_DIM]) {
        *out = [0.0; FEATURE_DIM];
        let slot = match self.script.phase() {
            Phase::Approach => Some(0),
            Phase::Descend => Some(1),
            Phase::Close => Some(2),
            Phase::Lift => Some(3),
            Phase::Hold => Some(4),
            Phase::Plan | Phase::Failed => None,
        };
        if let Some(i) = slot {
            out[i] = 1.0;
        }
        if let Some(p) = self.script.planned_on() {
            let now = obs.object_position();
            let moved = [0, 1, 2].map(|i| now[i] - p.position[i]);
            let moved = self.mount.table_in_base.inverse().transform_vector(moved);
            for i in 0..3 {
                out[5 + i] = moved[i] / self.limits.max_offset;
            }
            out[8] = wrap_quarter(obs.object_yaw - p.yaw) / self.limits.max_yaw;
        }
        let c = self.limits.normalized(&self.script.correction());
        out[9..13].copy_from_slice(&c);
        out[13] = self.close_signal;
        if let (Some(w), Some(p)) = (obs.wrist_camera, self.script.planned_on()) {
            let offset = [0, 1, 2].map(|i| w.position[i] - p.position[i]);
            let offset = self.mount.table_in_base.inverse().transform_vector(offset);
            out[14] = 1.0;
            for i in 0..3 {
                out[15 + i] = offset[i] / self.limits.max_offset;
            }
            out[18] = wrap_quarter(w.yaw - p.yaw) / self.limits.max_yaw;
        }
    }

    fn feature_names(&self) -> &'static [&'static str; FEATURE_DIM] {
        &FEATURE_NAMES
    }

    fn feature_bounds(&self, object_bound: f64) -> [(f64, f64); FEATURE_DIM] {
        // A difference of two cube positions, turned into the table frame: at most
        // √3 · 2 · object_bound per coordinate, in units of the largest offset.
        let moved = 2.0 * 3f64.sqrt() * object_bound / self.limits.max_offset;
        // `wrap_quarter` keeps a yaw difference within ±45°.
        let turned = std::f64::consts::FRAC_PI_4 / self.limits.max_yaw;
        let mut b = [(-1.0, 1.0); FEATURE_DIM];
        b[..5].fill((0.0, 1.0));
        b[5..8].fill((-moved, moved));
        b[8] = (-turned, turned);
        b[14] = (0.0, 1.0);
        b[15..18].fill((-moved, moved));
        b[18] = (-turned, turned);
        b
    }

    fn output_names(&self) -> [&'static str; OUTPUT_DIM] {
        let squeeze = if self.squeeze.is_some() {
            "squeeze"
        } else {
            "unused_4"
        };
        [
            "offset_x",
            "offset_y",
            "offset_z",
            "offset_yaw",
            squeeze,
            "unused_5",
            "close_timing",
        ]
    }

    fn phase(&self) -> &'static str {
        self.script.phase().name()
    }

    fn gave_up(&self) -> Option<Outcome> {
        self.script.gave_up()
    }

    /// The grip force per finger \[N\] the squeeze asks for (None without the squeeze).
    fn grip_force(&self) -> Option<f64> {
        let s = self.squeeze?;
        let force = if s.signal >= 0.0 {
            s.base + s.signal * self.limits.max_squeeze
        } else {
            s.base + s.signal * (s.base - MIN_GRIP_FORCE).max(0.0)
        };
        Some(force.max(MIN_GRIP_FORCE))
    }
}

/// The hand-written oracle residual: it steers the correction toward the true cube's offset
/// from the one the script planned on, through the same [`ResidualScript`] interface a learned
/// residual uses. If it cannot reach the oracle script's success, the interface cannot express
/// the fix.
pub struct OracleResidual {
    residual: ResidualScript,
    truth: Option<ObservedObject>,
    /// The squeeze command it holds (entry 4; 0 without the squeeze).
    squeeze: f64,
}

impl OracleResidual {
    pub fn new(env: &EnvConfig) -> Self {
        Self {
            residual: ResidualScript::new(env),
            truth: None,
            squeeze: 0.0,
        }
    }

    /// The same oracle with the squeeze, holding the command `squeeze` (in [-1, 1]) on it: the
    /// gate of the contact family (a fixed squeeze; it knows nothing of the cube's mass).
    pub fn squeezing(env: &EnvConfig, squeeze: f64) -> Self {
        Self {
            residual: ResidualScript::new(env).squeezing(env),
            truth: None,
            squeeze: squeeze.clamp(-1.0, 1.0),
        }
    }

    /// The command for the correction that puts the grasp on the true cube.
    fn action(&self) -> [f64; 7] {
        let mut a = [0.0; 7];
        a[4] = self.squeeze;
        let (Some(truth), Some(planned)) = (self.truth, self.residual.script().planned_on()) else {
            return a;
        };
        let moved = [0, 1, 2].map(|i| truth.position[i] - planned.position[i]);
        let moved = self
            .residual
            .mount
            .table_in_base
            .inverse()
            .transform_vector(moved);
        let want = TaskCorrection {
            offset: moved,
            yaw: wrap_quarter(truth.yaw - planned.yaw),
        };
        let n = self.residual.limits().normalized(&want);
        a[..4].copy_from_slice(&n);
        a.map(|v| v.clamp(-1.0, 1.0))
    }
}

impl Policy for OracleResidual {
    fn reset(&mut self, seed: u64) {
        self.residual.reset(seed);
        self.truth = None;
    }

    fn observe_truth(&mut self, truth: &ObservedObject) {
        self.truth = Some(*truth);
    }

    fn act(&mut self, obs: &Observation) -> Action {
        let a = self.action();
        self.residual.act(obs, &a)
    }

    fn gave_up(&self) -> Option<Outcome> {
        self.residual.script().gave_up()
    }

    fn phase(&self) -> Option<&'static str> {
        Some(self.residual.script().phase().name())
    }

    fn grip_force(&self) -> Option<f64> {
        self.residual.grip_force()
    }
}
