//! The interface a residual policy corrects the place task's engineered control through: the
//! force-guided search ([`crate::place::search`], tuned defaults) with a task-space correction
//! of the search's offset (`agent.action_space = "tcp"` in residual mode on a place preset).
//! An all-zero action is the engineer's search exactly, so an untrained residual starts from
//! the strongest hand-written control, not from the open loop (Johannink et al. 2019).
//!
//! Each step the policy's action (7 values in [-1, 1]) is read as: entries 0–3 a command for the
//! [`TaskCorrection`](crate::TaskCorrection) added to the search's offset (TCP along the table
//! frame's x, y, z and yaw about its vertical, × [`place_limits`]' largest values), through the
//! same filter and rate limits as the lift residual's ([`CorrectionLimits::follow`]); entries 4–6
//! scale the search's floor band, its pace along the spiral and its touch force, each by a
//! factor 2^(± [`MODULATION_OCTAVES`]) ([`Modulation`]), from that step on (0: the search as
//! tuned). The correction moves only while the search runs and is held from then on.
//!
//! The policy sees, besides the observation, [`FEATURE_DIM`] values ([`FEATURE_NAMES`]): the
//! script's phase, the wrist force in the table frame (in units of the search's contact force;
//! the search itself reads only its vertical part), where the search is (its spiral offset and
//! depth), the correction so far, and what the cycle has felt: the first touch's depth
//! against the rim's (a tilted cube's corner meets the rim higher or dips lower than a flat
//! face), the largest upward force, and the time since the reset against the takt.

use fairgrasp_env::cell::Cell;
use fairgrasp_env::episode::{Outcome, Policy};
use fairgrasp_env::{Action, EnvConfig, Mount, Observation};

use crate::correction::CorrectionLimits;
use crate::place::script::{PlacePhase, ScriptedPlace};
use crate::place::search::{Modulation, SearchParams};
pub use crate::task_residual::FEATURE_DIM;
use crate::task_residual::{OUTPUT_DIM, TaskResidual};

/// Names of the added values, in order.
pub const FEATURE_NAMES: [&str; FEATURE_DIM] = [
    "place_phase_grasp",
    "place_phase_carry",
    "place_phase_search_descend",
    "place_phase_search_spiral",
    "place_phase_search_insert",
    "place_phase_release",
    "wrist_force_x",
    "wrist_force_y",
    "wrist_force_z",
    "search_x",
    "search_y",
    "search_depth",
    "correction_x",
    "correction_y",
    "correction_z",
    "correction_yaw",
    "first_touch_below_rim",
    "peak_force",
    "cycle_time",
];

/// The search's settings a place residual scales (entries 4–6 of its action) range over
/// 2^(±this) times their tuned values.
pub const MODULATION_OCTAVES: f64 = 1.5;

/// The wrist-force features are clipped to ± this many contact forces (a hard press on the rim
/// reads 10–20 N; the policy needs the direction, not the magnitude of a jam).
pub const FORCE_FEATURE_BOUND: f64 = 10.0;
/// The search-depth feature is clipped to ± this (in wall heights from the floor).
pub const DEPTH_FEATURE_BOUND: f64 = 5.0;
/// The spiral-offset features are clipped to ± this (in units of the largest spiral radius).
pub const SPIRAL_FEATURE_BOUND: f64 = 1.5;

/// How far and how fast a place residual may correct the search: 6 mm in the plane (three
/// times the clearance; the families' errors are N(0, 3 mm)), 4 mm up or down, 4° of yaw, at
/// most 2 cm/s and 6°/s, through a 0.25 s filter.
pub fn place_limits() -> CorrectionLimits {
    CorrectionLimits {
        max_offset: 0.006,
        max_height: 0.004,
        max_yaw: 4f64.to_radians(),
        speed: 0.02,
        yaw_rate: 6f64.to_radians(),
        time_constant: 0.25,
        max_squeeze: 0.0,
    }
}

/// The force-guided search under a residual's correction.
pub struct PlaceResidual {
    script: ScriptedPlace,
    params: SearchParams,
    limits: CorrectionLimits,
    mount: Mount,
    wall_height: f64,
    /// Duration of one env step \[s\].
    step_dt: f64,
    /// Env steps since the reset.
    steps: usize,
    /// The cell's takt \[s\] (the cycle-time feature's unit).
    takt: f64,
}

impl PlaceResidual {
    /// The search tuned for the env `env`'s family (its `[task.place.search]`) and
    /// [`place_limits`].
    pub fn new(env: &EnvConfig) -> Self {
        let place = &env.task.place;
        let params = place.search;
        let script = ScriptedPlace::with_search(env, params);
        Self::over(env, script, params, place.wall_height, place.takt)
    }

    /// The residual interface over `script`, a place script searching with `params`, its depth
    /// features in units of `wall_height` \[m\] (the pocket's walls; on the stack task, which
    /// has none, [`crate::stack`] gives a unit of its own), on a cell whose takt is `takt` \[s\],
    /// with [`place_limits`].
    pub fn over(
        env: &EnvConfig,
        script: ScriptedPlace,
        params: SearchParams,
        wall_height: f64,
        takt: f64,
    ) -> Self {
        Self {
            script,
            params,
            limits: place_limits(),
            mount: Cell::from_config(env).mount,
            wall_height,
            step_dt: env.physics.dt * env.physics.substeps as f64,
            steps: 0,
            takt,
        }
    }

    /// The script inside.
    pub fn script(&self) -> &ScriptedPlace {
        &self.script
    }

    pub fn limits(&self) -> &CorrectionLimits {
        &self.limits
    }
}

impl TaskResidual for PlaceResidual {
    fn reset(&mut self, seed: u64) {
        self.script.reset(seed);
        self.steps = 0;
    }

    /// The env action for the policy's `action` at `obs` (module doc).
    fn act(&mut self, obs: &Observation, action: &[f64; OUTPUT_DIM]) -> Action {
        if self.script.place_phase() == PlacePhase::Search {
            let now = self.script.search_correction();
            let c = self.limits.follow(&now, action, self.step_dt);
            self.script.set_search_correction(c);
        }
        let factor = |a: f64| (a.clamp(-1.0, 1.0) * MODULATION_OCTAVES).exp2();
        self.script.set_search_modulation(Modulation {
            floor_band: factor(action[4]),
            spiral_pace: factor(action[5]),
            touch_force: factor(action[6]),
        });
        self.steps += 1;
        self.script.act(obs)
    }

    /// Writes the [`FEATURE_NAMES`] values for the next decision at `obs` into `out`.
    fn write_features(&self, obs: &Observation, out: &mut [f64; FEATURE_DIM]) {
        *out = [0.0; FEATURE_DIM];
        let search = self.script.search();
        let phase = match (self.script.place_phase(), search) {
            (PlacePhase::Grasp, _) => Some(0),
            (PlacePhase::Carry, _) => Some(1),
            (PlacePhase::Search, Some(s)) => Some(2 + s.stage_index().min(2)),
            (PlacePhase::Release | PlacePhase::Retreat | PlacePhase::Done, _) => Some(5),
            _ => None,
        };
        if let Some(i) = phase {
            out[i] = 1.0;
        }
        let to_table = self.mount.table_in_base.inverse();
        if let Some(f) = obs.wrist_force {
            let f = to_table.transform_vector(f);
            for i in 0..3 {
                out[6 + i] = (f[i] / self.params.contact_force)
                    .clamp(-FORCE_FEATURE_BOUND, FORCE_FEATURE_BOUND);
            }
        }
        if let Some(s) = search {
            let [x, y, depth] = s.last_offset();
            let spiral = |v: f64| {
                (v / self.params.max_radius).clamp(-SPIRAL_FEATURE_BOUND, SPIRAL_FEATURE_BOUND)
            };
            out[9] = spiral(x);
            out[10] = spiral(y);
            out[11] = ((s.floor_depth() - depth) / self.wall_height)
                .clamp(-DEPTH_FEATURE_BOUND, DEPTH_FEATURE_BOUND);
        }
        let c = self.limits.normalized(&self.script.search_correction());
        out[12..16].copy_from_slice(&c);
        if let Some(s) = search {
            if let Some(below) = s.first_touch_below_rim() {
                out[16] = (below / self.wall_height).clamp(-1.0, 1.0);
            }
            out[17] = (s.peak_force() / self.params.contact_force).clamp(0.0, FORCE_FEATURE_BOUND);
        }
        out[18] = (self.steps as f64 * self.step_dt / self.takt).min(2.0);
    }

    fn feature_names(&self) -> &'static [&'static str; FEATURE_DIM] {
        &FEATURE_NAMES
    }

    fn feature_bounds(&self, _object_bound: f64) -> [(f64, f64); FEATURE_DIM] {
        feature_bounds()
    }

    fn output_names(&self) -> [&'static str; OUTPUT_DIM] {
        [
            "search_offset_x",
            "search_offset_y",
            "search_offset_z",
            "search_offset_yaw",
            "search_floor_band",
            "search_spiral_pace",
            "search_touch_force",
        ]
    }

    /// The script's verdict (it gave up).
    fn gave_up(&self) -> Option<Outcome> {
        self.script.gave_up()
    }

    /// The script's phase name (for recorded trajectories).
    fn phase(&self) -> &'static str {
        Policy::phase(&self.script).unwrap_or("place")
    }
}

/// The bounds of each [`FEATURE_NAMES`] value, in order (what [`PlaceResidual::write_features`]
/// can write).
pub fn feature_bounds() -> [(f64, f64); FEATURE_DIM] {
    let mut b = [(-1.0, 1.0); FEATURE_DIM];
    for slot in &mut b[..6] {
        *slot = (0.0, 1.0);
    }
    for slot in &mut b[6..9] {
        *slot = (-FORCE_FEATURE_BOUND, FORCE_FEATURE_BOUND);
    }
    b[9] = (-SPIRAL_FEATURE_BOUND, SPIRAL_FEATURE_BOUND);
    b[10] = (-SPIRAL_FEATURE_BOUND, SPIRAL_FEATURE_BOUND);
    b[11] = (-DEPTH_FEATURE_BOUND, DEPTH_FEATURE_BOUND);
    b[17] = (0.0, FORCE_FEATURE_BOUND);
    b[18] = (0.0, 2.0);
    b
}
