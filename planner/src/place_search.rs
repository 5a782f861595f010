//! The force-guided search an integrator programs for a tight insertion, using only what a
//! real cell measures (the joints and a tared wrist force/torque sensor): from above the
//! pocket's estimated centre, descend slowly until the wrist feels the cube touch something;
//! touched at the pocket's floor, it is in; touched higher (on the rim), move the cube along an
//! Archimedean spiral in the table plane while holding the press at the touch's force (an
//! admittance in the vertical: the TCP goes down when the wrist feels less, up when it feels
//! more), until the TCP has sunk half a wall's height below the touch (the cube has found the
//! opening), then descend into it. The release and retreat follow, as in
//! the open-loop script ([`crate::place`]).
//!
//! The TCP follows a task-space offset from the carry pose (`corrected`, through the arm's
//! Jacobian), one env step at a time. Its parameters ([`SearchParams`]) are tuned on training
//! scenarios by a grid search (`fairgrasp baseline --script force_search --search …`,
//! docs/place.md).

use fairgrasp_env::config::SearchTuning;
use fairgrasp_env::{EnvConfig, Observation};
use fairgrasp_kinematics::{ArmModel, Pose};
use serde::Serialize;

use crate::correction::{TaskCorrection, corrected};

/// The search's settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SearchParams {
    /// Descent speed \[m/s\].
    pub descend_speed: f64,
    /// Upward wrist force that counts as a touch \[N\].
    pub contact_force: f64,
    /// The admittance of the press while spiralling: the TCP's vertical speed per newton of
    /// force below `contact_force` \[m/s/N\] (capped at `descend_speed` either way).
    pub admittance: f64,
    /// The spiral's pitch: its radius grows this much per turn \[m\].
    pub pitch: f64,
    /// The spiral's speed along its path \[m/s\].
    pub speed: f64,
    /// The largest spiral radius searched before giving up (the cube is released where it is)
    /// \[m\].
    pub max_radius: f64,
    /// A touch within this height above the floor's depth counts as the cube on the floor (it
    /// is in); a higher one is the rim, and the spiral starts \[m\]. `None`: half the wall.
    pub floor_band: Option<f64>,
}

impl Default for SearchParams {
    /// The settings tuned on `place_grasp_error` and `place_fixture_error`
    /// ([`SearchTuning::default`]) and the untuned rest.
    fn default() -> Self {
        let tuned = SearchTuning::default();
        Self {
            descend_speed: 0.01,
            contact_force: tuned.contact_force,
            admittance: 0.004,
            pitch: tuned.pitch,
            speed: tuned.speed,
            max_radius: 0.009,
            floor_band: tuned.floor_band,
        }
    }
}

impl SearchParams {
    /// The search as tuned for the env's family (`[task.place.search]`), the rest default.
    pub fn tuned_for(env: &EnvConfig) -> Self {
        let t = &env.task.place.search;
        Self {
            contact_force: t.contact_force,
            pitch: t.pitch,
            speed: t.speed,
            floor_band: t.floor_band,
            ..Self::default()
        }
    }
}

/// Where the search is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// Going down from the carry pose; `depth` how far \[m\].
    Descend { depth: f64 },
    /// On the rim, touched at `touch` \[m\] below the carry pose, now at `depth`, `time` \[s\] into
    /// the spiral.
    Spiral { touch: f64, depth: f64, time: f64 },
    /// Found: going down into the pocket.
    Insert { depth: f64 },
    /// At the floor, or given up: the search's work is done.
    Done,
}

/// A running search, from the carry pose's joints `carry` \[rad\], `to_floor` \[m\] above the
/// depth where the cube sits just above the pocket's floor.
pub struct ForceSearch {
    params: SearchParams,
    carry: [f64; 6],
    /// Depth below the carry pose where the cube's bottom is just above the floor \[m\].
    floor_depth: f64,
    /// Depths above this are touches on the rim, not on the floor \[m\].
    rim_below: f64,
    /// The pocket's depth \[m\].
    wall_height: f64,
    stage: Stage,
    /// The xy offset of the spiral when the press gave way \[m, table frame\].
    found_xy: [f64; 2],
    step_dt: f64,
    /// A residual's correction added to the search's own offset (zero for the engineer's
    /// search; [`crate::place_residual`]).
    correction: TaskCorrection,
    /// The offset the last step commanded: xy in the table plane, then depth below the carry
    /// pose \[m\].
    last: [f64; 3],
}

impl ForceSearch {
    /// A search starting at the carry pose `carry` \[rad\], the floor `floor_depth` \[m\] below it,
    /// the rim's top `wall_height` \[m\] above the floor.
    pub fn new(
        params: SearchParams,
        carry: [f64; 6],
        floor_depth: f64,
        wall_height: f64,
        step_dt: f64,
    ) -> Self {
        Self {
            params,
            carry,
            floor_depth,
            rim_below: floor_depth - params.floor_band.unwrap_or(0.5 * wall_height),
            wall_height,
            stage: Stage::Descend { depth: 0.0 },
            found_xy: [0.0; 2],
            step_dt,
            correction: TaskCorrection::ZERO,
            last: [0.0; 3],
        }
    }

    /// Adds `c` to the search's own offset from the next step on (a residual's correction).
    pub fn set_correction(&mut self, c: TaskCorrection) {
        self.correction = c;
    }

    /// The search's own offset at the last step: xy in the table plane and the depth below the
    /// carry pose \[m\] (without the correction).
    pub fn last_offset(&self) -> [f64; 3] {
        self.last
    }

    /// The depth below the carry pose where the cube sits just above the floor \[m\].
    pub fn floor_depth(&self) -> f64 {
        self.floor_depth
    }

    /// The stage as an index: 0 descend, 1 spiral, 2 insert, 3 done.
    pub fn stage_index(&self) -> usize {
        match self.stage {
            Stage::Descend { .. } => 0,
            Stage::Spiral { .. } => 1,
            Stage::Insert { .. } => 2,
            Stage::Done => 3,
        }
    }

    /// Has the search finished (the cube at the floor, or the spiral exhausted)?
    pub fn done(&self) -> bool {
        self.stage == Stage::Done
    }

    /// The stage's name, for trajectories.
    pub fn stage_name(&self) -> &'static str {
        match self.stage {
            Stage::Descend { .. } => "search_descend",
            Stage::Spiral { .. } => "search_spiral",
            Stage::Insert { .. } => "search_insert",
            Stage::Done => "search_done",
        }
    }

    /// The spiral's offset in the table plane after `time` \[s\] (radius `pitch·θ/2π`, the
    /// path's length `speed·time` ≈ `pitch·θ²/4π`).
    fn spiral(&self, time: f64) -> [f64; 2] {
        let p = &self.params;
        let theta = (4.0 * std::f64::consts::PI * p.speed * time / p.pitch).sqrt();
        let r = p.pitch * theta / std::f64::consts::TAU;
        [r * theta.cos(), r * theta.sin()]
    }

    /// Advances the search by one env step on what the wrist feels in `obs` (its push along
    /// the table's vertical); returns the joints the arm should reach by the next step.
    pub fn step(&mut self, obs: &Observation, model: &ArmModel, table_in_base: &Pose) -> [f64; 6] {
        let up = obs.wrist_force.map_or(0.0, |f| {
            let z = table_in_base.transform_vector([0.0, 0.0, 1.0]);
            f[0] * z[0] + f[1] * z[1] + f[2] * z[2]
        });
        let p = self.params;
        let touched = up > p.contact_force;
        let down = p.descend_speed * self.step_dt;
        let (xy, depth) = match self.stage {
            Stage::Descend { depth } if touched && depth < self.rim_below => {
                self.stage = Stage::Spiral {
                    touch: depth,
                    depth,
                    time: 0.0,
                };
                ([0.0; 2], depth)
            }
            Stage::Descend { depth } if touched || depth >= self.floor_depth => {
                self.stage = Stage::Done;
                ([0.0; 2], depth)
            }
            Stage::Descend { depth } => {
                let d = (depth + down).min(self.floor_depth);
                self.stage = Stage::Descend { depth: d };
                ([0.0; 2], d)
            }
            Stage::Insert { depth } if depth >= self.floor_depth => {
                self.stage = Stage::Done;
                (self.found_xy, depth)
            }
            Stage::Insert { depth } => {
                let d = (depth + down).min(self.floor_depth);
                self.stage = Stage::Insert { depth: d };
                (self.found_xy, d)
            }
            Stage::Spiral { touch, depth, time } => {
                let here = self.spiral(time);
                let sink =
                    (p.admittance * (p.contact_force - up) * self.step_dt).clamp(-down, down);
                let d = (depth + sink).min(self.floor_depth);
                if d - touch > 0.5 * self.wall_height {
                    // Sunk below the rim: the cube is over the opening.
                    self.found_xy = here;
                    self.stage = Stage::Insert { depth: d };
                    (here, d)
                } else if here[0].hypot(here[1]) > p.max_radius {
                    self.stage = Stage::Done;
                    (here, d)
                } else {
                    let t = time + self.step_dt;
                    self.stage = Stage::Spiral {
                        touch,
                        depth: d,
                        time: t,
                    };
                    (self.spiral(t), d)
                }
            }
            Stage::Done => (self.found_xy, self.floor_depth),
        };
        self.last = [xy[0], xy[1], depth];
        let k = &self.correction;
        let c = TaskCorrection {
            offset: [
                xy[0] + k.offset[0],
                xy[1] + k.offset[1],
                k.offset[2] - depth,
            ],
            yaw: k.yaw,
        };
        corrected(model, table_in_base, &self.carry, &c)
    }
}
