//! The force-guided search an integrator programs for a tight insertion, using only what a
//! real cell measures (the joints and a tared wrist force/torque sensor): from above the
//! pocket's estimated centre, descend slowly until the wrist feels the cube touch something;
//! touched at the pocket's floor, it is in; touched higher (on the rim), move the cube along an
//! Archimedean spiral in the table plane while holding the press at the touch's force (an
//! admittance in the vertical: the TCP goes down when the wrist feels less, up when it feels
//! more), until the TCP has sunk half a wall's height below the touch (the cube has found the
//! opening), then descend into it. The release and retreat follow, as in
//! the open-loop script ([`crate::place::script`]).
//!
//! The TCP follows a task-space offset from the carry pose (`corrected`, through the arm's
//! Jacobian), one env step at a time. Its parameters ([`SearchParams`], the preset's
//! `[task.place.search]`) are tuned on training scenarios by `fairgrasp tune` (docs/place.md).

use fairgrasp_env::Observation;
pub use fairgrasp_env::config::SearchParams;
use fairgrasp_kinematics::{ArmModel, Pose};

use crate::correction::{TaskCorrection, corrected};

/// The cube's bottom above the pocket's floor when the gripper opens \[m\] (the place
/// script's place pose, and the search's floor depth).
pub const DROP_HEIGHT: f64 = 0.002;

/// What the wrist feels pushing up along the table's vertical in `obs` \[N\] (0 without a
/// wrist sensor); `table_in_base` is the table frame in `base_link`.
pub fn upward_force(obs: &Observation, table_in_base: &Pose) -> f64 {
    obs.wrist_force.map_or(0.0, |f| {
        let z = table_in_base.transform_vector([0.0, 0.0, 1.0]);
        f[0] * z[0] + f[1] * z[1] + f[2] * z[2]
    })
}

/// Where the search is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// Going down from the carry pose; `depth` how far \[m\].
    Descend { depth: f64 },
    /// On the rim, touched at `touch` \[m\] below the carry pose, now at `depth`, `time` \[s\] into
    /// the spiral.
    Spiral { touch: f64, depth: f64, time: f64 },
    /// Found: going down into the pocket, from the spiral's `time` \[s\] (where it goes on if
    /// the find proves false, [`SearchParams::check_floor`]).
    Insert { depth: f64, time: f64 },
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
    /// The pocket's depth \[m\].
    wall_height: f64,
    stage: Stage,
    /// The xy offset of the spiral when the press gave way \[m, table frame\].
    found_xy: [f64; 2],
    step_dt: f64,
    /// A residual's correction added to the search's own offset (zero for the engineer's
    /// search; [`crate::place::residual`]).
    correction: TaskCorrection,
    /// The offset the last step commanded: xy in the table plane, then depth below the carry
    /// pose \[m\].
    last: [f64; 3],
    /// The switching search's rule, until its first touch: a touch farther than the band
    /// \[m\] from the rim's height switches to the tilted cube's settings.
    switch: Option<(f64, SearchParams)>,
    /// What the switch read the cycle as at the first touch: `Some(true)` tilted.
    read_tilted: Option<bool>,
    /// A residual's scaling of the settings ([`Modulation`]).
    modulation: Modulation,
    /// Depth of the first touch below the carry pose \[m\].
    first_touch: Option<f64>,
    /// The largest upward wrist force so far \[N\].
    peak_force: f64,
}

/// Factors on the search's settings, set each step by a residual: 1 leaves a setting as it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Modulation {
    /// On the floor band (how near the floor a touch counts as the cube in).
    pub floor_band: f64,
    /// On the pace along the spiral (its speed; the path stays the same).
    pub spiral_pace: f64,
    /// On the touch force (what counts as a touch, and the press the spiral holds).
    pub touch_force: f64,
}

impl Modulation {
    /// The search as set.
    pub const NONE: Modulation = Modulation {
        floor_band: 1.0,
        spiral_pace: 1.0,
        touch_force: 1.0,
    };
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
            wall_height,
            stage: Stage::Descend { depth: 0.0 },
            found_xy: [0.0; 2],
            step_dt,
            correction: TaskCorrection::ZERO,
            last: [0.0; 3],
            switch: None,
            read_tilted: None,
            modulation: Modulation::NONE,
            first_touch: None,
            peak_force: 0.0,
        }
    }

    /// Scales the search's settings from the next step on (a residual's adaptation): the floor
    /// band, the spiral's pace along its path, the touch force; [`Modulation::NONE`] is the
    /// search as set.
    pub fn set_modulation(&mut self, m: Modulation) {
        self.modulation = m;
    }

    /// The depth below the carry pose of the first touch, relative to where a flat cube meets
    /// the rim \[m\] (positive: deeper; `None` before a touch).
    pub fn first_touch_below_rim(&self) -> Option<f64> {
        self.first_touch.map(|d| d - self.rim_contact_depth())
    }

    /// The largest upward wrist force felt so far \[N\].
    pub fn peak_force(&self) -> f64 {
        self.peak_force
    }

    /// Depths above this are touches on the rim, not on the floor \[m\].
    fn rim_below(&self) -> f64 {
        // A factor of 1 is exact: the search as set, to the bit.
        let band = self.params.floor_band.unwrap_or(0.5 * self.wall_height);
        self.floor_depth - band * self.modulation.floor_band
    }

    /// Where a flat cube's face meets the rim's top, below the carry pose \[m\] (the floor
    /// depth leaves the cube DROP_HEIGHT above the floor).
    fn rim_contact_depth(&self) -> f64 {
        self.floor_depth + DROP_HEIGHT - self.wall_height
    }

    /// The switching search: these settings until the first touch; a touch farther than
    /// `tilt_band` \[m\] above or below the rim's height (a tilted cube's corner meets the rim
    /// or dips into the pocket before a flat face would) switches to `tilted`.
    pub fn with_switch(mut self, tilt_band: f64, tilted: SearchParams) -> Self {
        self.switch = Some((tilt_band, tilted));
        self
    }

    /// What the switching search read the cycle as at its first touch (`Some(true)`: a tilted
    /// cube); `None` before the touch, or without a switch.
    pub fn read_tilted(&self) -> Option<bool> {
        self.read_tilted
    }

    /// At the first touch, at `depth` below the carry pose \[m\]: reads the cycle and switches.
    fn switch_at_touch(&mut self, depth: f64) {
        let Some((band, tilted)) = self.switch.take() else {
            return;
        };
        let is_tilted = (depth - self.rim_contact_depth()).abs() > band;
        self.read_tilted = Some(is_tilted);
        if is_tilted {
            self.params = tilted;
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
        let up = upward_force(obs, table_in_base);
        // A factor of 1 is exact: the search as set, to the bit.
        let contact_force = self.params.contact_force * self.modulation.touch_force;
        let touched = up > contact_force;
        self.peak_force = self.peak_force.max(up);
        if let (true, Stage::Descend { depth }) = (touched, self.stage) {
            self.first_touch.get_or_insert(depth);
            self.switch_at_touch(depth);
        }
        let p = self.params;
        let rim_below = self.rim_below();
        let down = p.descend_speed * self.step_dt;
        let (xy, depth) = match self.stage {
            Stage::Descend { depth } if touched && depth < rim_below => {
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
            Stage::Insert { depth, .. } if depth >= self.floor_depth => {
                self.stage = Stage::Done;
                (self.found_xy, depth)
            }
            Stage::Insert { depth, time } if p.check_floor && touched && depth < rim_below => {
                // Stopped above the floor: a false find; the spiral goes on from there.
                self.stage = Stage::Spiral {
                    touch: depth,
                    depth,
                    time,
                };
                (self.found_xy, depth)
            }
            Stage::Insert { depth, time } => {
                let d = (depth + down).min(self.floor_depth);
                self.stage = Stage::Insert { depth: d, time };
                (self.found_xy, d)
            }
            Stage::Spiral { touch, depth, time } => {
                let here = self.spiral(time);
                let sink = (p.admittance * (contact_force - up) * self.step_dt).clamp(-down, down);
                let d = (depth + sink).min(self.floor_depth);
                if d - touch > 0.5 * self.wall_height {
                    // Sunk below the rim: the cube is over the opening.
                    self.found_xy = here;
                    self.stage = Stage::Insert { depth: d, time };
                    (here, d)
                } else if here[0].hypot(here[1]) > p.max_radius {
                    self.stage = Stage::Done;
                    (here, d)
                } else {
                    let t = time + self.step_dt * self.modulation.spiral_pace;
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
