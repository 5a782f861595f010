//! Squaring a cube that hangs tilted in the grip ([`Squaring`], the "search + squaring"
//! control's first step; settings [`SquareParams`], `[task.place.square]`): from a carry pose
//! above free table beside the pocket, lower the cube until it would stand flat on the table
//! and press a little deeper (or until the wrist feels the press's force limit), hold, and lift
//! back to the carry pose. A tilted cube's low corner meets the table first; pressed further, the
//! cube turns in the fingers about the pads' axis until its face lies flat, which is how an
//! integrator squares a part in the gripper against a fixed surface (extrinsic dexterity).

use fairgrasp_env::Observation;
pub use fairgrasp_env::config::SquareParams;
use fairgrasp_kinematics::{ArmModel, Pose};

use crate::correction::{TaskCorrection, corrected};
use crate::place::search::upward_force;

/// After the hold, the full squeeze is back this long before the lift \[s\] (the fingers'
/// force settles in a few steps).
const REGRIP_TIME: f64 = 0.25;

/// Where the squaring is.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// Going down, `depth` below the carry pose \[m\].
    Press {
        depth: f64,
    },
    /// Holding at `depth` for `time` \[s\] so far.
    Hold {
        depth: f64,
        time: f64,
    },
    /// Going back up.
    Rise {
        depth: f64,
    },
    Done,
}

/// A running squaring from the carry pose `carry` \[rad\].
pub struct Squaring {
    params: SquareParams,
    carry: [f64; 6],
    /// Depth below the carry pose at which the cube would stand flat on the table, plus the
    /// press \[m\].
    press_depth: f64,
    stage: Stage,
    step_dt: f64,
    /// Half the cube's edge \[m\].
    half_cube: f64,
    /// Where the TCP held the cube above its centre while the cube stood on the table, measured
    /// at the end of the hold \[m\] (`None` before).
    grasp_height_seen: Option<f64>,
}

impl Squaring {
    /// A squaring from `carry` \[rad\], where the cube's bottom would touch the table, were it
    /// flat, `flat_depth` \[m\] lower.
    /// `cube_size` \[m\] is the cube's edge.
    pub fn new(
        params: SquareParams,
        carry: [f64; 6],
        flat_depth: f64,
        step_dt: f64,
        cube_size: f64,
    ) -> Self {
        Self {
            params,
            carry,
            press_depth: flat_depth + params.press,
            stage: Stage::Press { depth: 0.0 },
            step_dt,
            half_cube: 0.5 * cube_size,
            grasp_height_seen: None,
        }
    }

    /// How far above the cube's centre the TCP holds it, as measured while the cube stood on
    /// the table \[m\]: pressing may have slid it along the pads, and the place that follows
    /// must know (an integrator's touch-off). `None` until the hold has ended.
    pub fn grasp_height_seen(&self) -> Option<f64> {
        self.grasp_height_seen
    }

    /// The squeeze per finger the squaring asks for now \[N\]: lowered while it presses and
    /// holds (`None`: the full squeeze, from the end of the hold on).
    pub fn squeeze(&self) -> Option<f64> {
        match self.stage {
            Stage::Press { .. } => Some(self.params.squeeze),
            Stage::Hold { time, .. } if time < self.params.hold => Some(self.params.squeeze),
            Stage::Hold { .. } | Stage::Rise { .. } | Stage::Done => None,
        }
    }

    /// Is the cube squared and lifted back?
    pub fn done(&self) -> bool {
        self.stage == Stage::Done
    }

    /// The stage's name, for trajectories.
    pub fn stage_name(&self) -> &'static str {
        match self.stage {
            Stage::Press { .. } => "square_press",
            Stage::Hold { .. } => "square_hold",
            Stage::Rise { .. } => "square_rise",
            Stage::Done => "square_done",
        }
    }

    /// Advances one env step on what the wrist feels in `obs` (its push along the table's
    /// vertical); returns the joints the arm should reach by the next step.
    pub fn step(&mut self, obs: &Observation, model: &ArmModel, table_in_base: &Pose) -> [f64; 6] {
        let up = upward_force(obs, table_in_base);
        let p = self.params;
        let dz = p.speed * self.step_dt;
        let depth = match self.stage {
            Stage::Press { depth } if depth >= self.press_depth || up > p.force => {
                self.stage = Stage::Hold { depth, time: 0.0 };
                depth
            }
            Stage::Press { depth } => {
                let d = (depth + dz).min(self.press_depth);
                self.stage = Stage::Press { depth: d };
                d
            }
            Stage::Hold { depth, time } if time >= p.hold + REGRIP_TIME => {
                let tcp = model.fk_tcp(&obs.joints);
                let above_table = table_in_base.inverse().transform_point(tcp.xyz())[2];
                self.grasp_height_seen = Some(above_table - self.half_cube);
                self.stage = Stage::Rise { depth };
                depth
            }
            Stage::Hold { depth, time } => {
                self.stage = Stage::Hold {
                    depth,
                    time: time + self.step_dt,
                };
                depth
            }
            Stage::Rise { depth } if depth <= 0.0 => {
                self.stage = Stage::Done;
                0.0
            }
            Stage::Rise { depth } => {
                let d = (depth - 2.0 * dz).max(0.0);
                self.stage = Stage::Rise { depth: d };
                d
            }
            Stage::Done => 0.0,
        };
        let c = TaskCorrection {
            offset: [0.0, 0.0, -depth],
            yaw: 0.0,
        };
        corrected(model, table_in_base, &self.carry, &c)
    }
}
