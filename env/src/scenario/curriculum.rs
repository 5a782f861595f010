//! A curriculum over the randomisation: fixed → position (optionally through sectors narrowed
//! around the fixed cube position first) → +yaw → +friction/mass, advancing when the rolling
//! success rate passes a threshold (optionally on each side of the fixed cube's bearing).

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use crate::config::RandomizationConfig;
use crate::config::check::{Bounds, check_in};

/// Curriculum settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CurriculumConfig {
    /// Advance when the success rate over the last `window` episodes reaches this (0–1).
    pub threshold: f64,
    /// Episodes in the rolling window.
    pub window: usize,
    /// Stages between `fixed` and `position` whose cube positions come from the sector narrowed
    /// around the fixed position: each value (in (0, 1), increasing) is the fraction of the way
    /// from the fixed position to the full sector's radius and angle ranges. Empty: straight
    /// from `fixed` to the whole sector.
    pub position_steps: Vec<f64>,
    /// Once cube positions vary, advance only when the cubes on *each* side of the fixed cube's
    /// bearing from the base (left and right) pass the threshold over their own window. Without
    /// it a policy that grasps on one side only (about half the episodes) can pass a 0.6
    /// threshold and carry the one-sided skill to the last stage.
    pub both_sides: bool,
}

impl Default for CurriculumConfig {
    fn default() -> Self {
        Self {
            threshold: 0.6,
            window: 50,
            position_steps: Vec::new(),
            both_sides: false,
        }
    }
}

impl CurriculumConfig {
    /// Checks the settings; the message names the field.
    pub fn validate(&self) -> Result<(), String> {
        check_in(
            self.threshold,
            "curriculum.threshold",
            Bounds::above_to(0.0, 1.0),
            "",
        )
        .and_then(|()| {
            check_in(
                self.window,
                "curriculum.window",
                Bounds::closed(1.0, 1e6).unit("episodes"),
                "",
            )
        })
        .map_err(|e| e.to_string())?;
        let ok = self.position_steps.iter().all(|f| *f > 0.0 && *f < 1.0)
            && self.position_steps.windows(2).all(|w| w[0] < w[1]);
        if !ok {
            return Err(format!(
                "curriculum.position_steps = {:?}: give increasing fractions inside (0, 1)",
                self.position_steps
            ));
        }
        Ok(())
    }
}

/// The stages after `fixed` and the narrowed sectors, in order.
const LATER_STAGES: [&str; 3] = ["position", "position+yaw", "position+yaw+friction/mass"];

/// Curriculum state: the stage and the recent outcomes.
#[derive(Clone, Debug, PartialEq)]
pub struct Curriculum {
    config: CurriculumConfig,
    target: RandomizationConfig,
    /// The cube position of the `fixed` stage, table frame \[m\] (`scene.cube_xy`).
    fixed_xy: [f64; 2],
    stage: usize,
    recent: VecDeque<bool>,
    /// Outcomes of cubes left of the fixed bearing (index 0) and right of it (index 1); used
    /// with `both_sides`.
    sides: [VecDeque<bool>; 2],
}

impl Curriculum {
    /// Starts at stage 0; `target` is the randomisation of the last stage, `fixed_xy` the cube
    /// position \[m\] of the first (`scene.cube_xy`).
    pub fn new(config: CurriculumConfig, target: RandomizationConfig, fixed_xy: [f64; 2]) -> Self {
        Self {
            config,
            target,
            fixed_xy,
            stage: 0,
            recent: VecDeque::new(),
            sides: [VecDeque::new(), VecDeque::new()],
        }
    }

    /// The same curriculum resumed at `stage` (clamped to the last), with empty windows.
    pub fn at_stage(mut self, stage: usize) -> Self {
        self.stage = stage.min(self.stage_count() - 1);
        self
    }

    /// The current stage index (0 … `stage_count() − 1`).
    pub fn stage(&self) -> usize {
        self.stage
    }

    /// Number of stages: fixed, the narrowed sectors, position, +yaw, +friction/mass.
    pub fn stage_count(&self) -> usize {
        1 + self.config.position_steps.len() + LATER_STAGES.len()
    }

    /// The name of stage `i` (e.g. `fixed`, `position 25 %`, `position+yaw`).
    pub fn stage_name(&self, i: usize) -> String {
        let steps = &self.config.position_steps;
        match i {
            0 => "fixed".into(),
            i if i <= steps.len() => format!("position {:.0} %", steps[i - 1] * 100.0),
            i => LATER_STAGES[(i - 1 - steps.len()).min(LATER_STAGES.len() - 1)].into(),
        }
    }

    /// Success rate over the window so far (0 when empty).
    pub fn success_rate(&self) -> f64 {
        rate(&self.recent)
    }

    /// Records an episode outcome without its cube position; returns true if this advanced the
    /// stage (see [`Curriculum::record_at`]).
    pub fn record(&mut self, success: bool) -> bool {
        self.record_at(success, None)
    }

    /// Records an episode outcome and where its cube was (table frame \[m\], if known); returns
    /// true if this advanced the stage. A stage advances only with a full window (with
    /// `both_sides`, once positions vary: a full window on each side, each passing the
    /// threshold); the windows then start empty again.
    pub fn record_at(&mut self, success: bool, object_xy: Option<[f64; 2]>) -> bool {
        let window = self.config.window;
        let push = |q: &mut VecDeque<bool>| {
            q.push_back(success);
            while q.len() > window {
                q.pop_front();
            }
        };
        push(&mut self.recent);
        if let Some(side) = object_xy.map(|xy| self.side_of(xy)) {
            push(&mut self.sides[side]);
        }
        let passes = |q: &VecDeque<bool>| q.len() == window && rate(q) >= self.config.threshold;
        let sided = self.config.both_sides && self.stage > 0;
        let ready = if sided {
            self.sides.iter().all(passes)
        } else {
            passes(&self.recent)
        };
        if ready && self.stage + 1 < self.stage_count() {
            self.stage += 1;
            self.recent.clear();
            self.sides.iter_mut().for_each(VecDeque::clear);
            return true;
        }
        false
    }

    /// Success rates over the left and right windows so far (0 when empty).
    pub fn side_success_rates(&self) -> [f64; 2] {
        [rate(&self.sides[0]), rate(&self.sides[1])]
    }

    /// 0 when `xy` lies left of (counter-clockwise from) the fixed cube's bearing from the
    /// base, 1 otherwise.
    fn side_of(&self, xy: [f64; 2]) -> usize {
        let bearing = self.fixed_xy[1].atan2(self.fixed_xy[0]);
        let a = xy[1].atan2(xy[0]) - bearing;
        let wrapped = a.sin().atan2(a.cos());
        usize::from(wrapped < 0.0)
    }

    /// The randomisation in force at the current stage.
    pub fn randomization(&self) -> RandomizationConfig {
        let t = &self.target;
        let none = RandomizationConfig {
            radius: t.radius,
            angle: t.angle,
            ..RandomizationConfig::default()
        };
        let narrowed = self.config.position_steps.len();
        let position = RandomizationConfig {
            position: t.position,
            joint_noise: t.joint_noise,
            ..none.clone()
        };
        match self.stage {
            0 => none,
            i if i <= narrowed => {
                let f = self.config.position_steps[i - 1];
                let [x, y] = self.fixed_xy;
                let (r0, a0) = (x.hypot(y), y.atan2(x));
                let toward = |from: f64, range: [f64; 2]| {
                    [from + f * (range[0] - from), from + f * (range[1] - from)]
                };
                RandomizationConfig {
                    radius: toward(r0, t.radius),
                    angle: toward(a0, t.angle),
                    ..position
                }
            }
            i if i == narrowed + 1 => position,
            i if i == narrowed + 2 => RandomizationConfig {
                yaw: t.yaw,
                ..position
            },
            _ => t.clone(),
        }
    }
}

/// The fraction of successes in `q` (0 when empty).
fn rate(q: &VecDeque<bool>) -> f64 {
    if q.is_empty() {
        0.0
    } else {
        q.iter().filter(|s| **s).count() as f64 / q.len() as f64
    }
}
