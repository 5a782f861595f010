//! Free-space steps: an env step of the servo arm that skips rigid-body simulation because
//! nothing can touch the object.
//!
//! While the object rests and every robot part stays clear of it, the physics has nothing to
//! compute that the kinematics does not already know: the links are wherever FK puts them and
//! the fingers follow their motor ([`crate::sim::finger_drive`]). Such a step integrates the robot
//! alone, then checks arm and gripper against the table and against themselves with the exact
//! collider shapes ([`RobotShapes`]), as the narrow phase would after the last substep.
//!
//! The step is decided by what happens in it, not guessed: the robot is advanced through every
//! substep, and if any part could have come within [`CONTACT_MARGIN`] of the object at any
//! moment (each part's motion during a substep is bounded by the joints' motion times their
//! reach, plus the fingers' travel), the robot is put back and the step runs physics instead.
//! Everything here is a pure function of the state, so seeded replays stay bit-identical.
//! Positions are in `world` \[m\].

use fairgrasp_kinematics::ArmModel;
use fairgrasp_kinematics::geometry::Cuboid;
use nalgebra::Isometry3;

use crate::config::EnvConfig;
use crate::robot::{MotionState, Robot};
use crate::sim::contacts::{CollisionFilter, ContactReport};
use crate::sim::part::Part;
use crate::sim::shapes::{CheckedPairs, RobotShapes};

/// The closest any robot part may come to the object, at any moment of a free-space step \[m\]:
/// closer than this, the step runs physics. rapier 0.36 makes speculative contacts out to 2 cm
/// (`normalized_prediction_distance` 0.02 × a 1 m length unit), but a contact farther than the
/// gap the bodies close within one substep exerts no force, and a free step moves only the
/// robot, bounded per substep by `FreeSpace::motion_bound`; the free-space equivalence tests
/// (`env/tests/free_space.rs`, `planner/tests/free_space.rs`) hold at this margin.
pub const CONTACT_MARGIN: f64 = 0.005;
/// Below these the object counts as at rest \[m/s, rad/s\] (a sleeping object always does).
pub const REST_SPEED: f64 = 0.002;
pub const REST_TURN_RATE: f64 = 0.02;

/// The free-space stepper of one env: the robot's shapes and how far its parts reach.
pub struct FreeSpace {
    shapes: RobotShapes,
    /// The robot–robot and robot–table pairs that count as collisions.
    pairs: CheckedPairs,
    /// Those of them rapier does not compute for the servo arm: both parts never moved by
    /// forces (links, palm, table; [`Part::never_moved_by_forces`]).
    kinematic_pairs: CheckedPairs,
    /// For joint i (0 = j1): an upper bound on the distance \[m\] from its axis to any point of
    /// the links and gripper it moves, for any joint angles.
    reach: [f64; 6],
    /// Half the cube's edge \[m\].
    object_half: f64,
}

impl FreeSpace {
    pub fn new(config: &EnvConfig, model: &ArmModel) -> FreeSpace {
        let pairs = CheckedPairs::new(&CollisionFilter::new(model));
        FreeSpace {
            shapes: RobotShapes::new(config, model),
            kinematic_pairs: pairs
                .only(|a, b| a.never_moved_by_forces() && b.never_moved_by_forces()),
            pairs,
            reach: joint_reach(model),
            object_half: config.scene.cube_size / 2.0,
        }
    }

    /// Tries to advance `robot` through `substeps` substeps of `dt` \[s\] toward `command`
    /// \[rad/s\] without physics, the object at `object` (world, at rest). Returns the step's
    /// contact report (table and self-collisions; no object contact by construction), or
    /// `None` with `robot` unchanged when something could touch the object: then the step
    /// must run physics.
    pub fn try_step(
        &mut self,
        robot: &mut Robot,
        object: &Isometry3<f64>,
        command: &[f64; 6],
        dt: f64,
        substeps: usize,
    ) -> Option<ContactReport> {
        let object = Cuboid {
            pose: *object,
            half_extents: [self.object_half; 3],
        };
        let start = robot.motion();
        let gravity = robot.finger_gravity();
        self.place(robot);
        let clearance = self.shapes.clearance_to(&object);
        // First pass without FK: how far can anything have moved during the whole step?
        let mut reach = 0.0_f64;
        for _ in 0..substeps {
            robot.free_substep(command, dt, gravity);
            reach = reach.max(self.motion_bound(&start, &robot.motion()));
        }
        if clearance < reach + CONTACT_MARGIN {
            // Close: check the clearance at every substep against that substep's motion.
            robot.set_motion(&start);
            let mut clearance = clearance;
            for _ in 0..substeps {
                let before = robot.motion();
                robot.free_substep(command, dt, gravity);
                if clearance < self.motion_bound(&before, &robot.motion()) + CONTACT_MARGIN {
                    robot.set_motion(&start);
                    return None;
                }
                self.place(robot);
                clearance = self.shapes.clearance_to(&object);
            }
            if clearance < CONTACT_MARGIN {
                robot.set_motion(&start);
                return None;
            }
        }
        self.place(robot);
        Some(ContactReport {
            collision: self.shapes.collision_among(&self.pairs),
            ..ContactReport::default()
        })
    }

    /// After a step that ran physics with the servo arm: the deepest collision among the pairs
    /// rapier leaves out (links and palm against each other and the table), with the robot
    /// where it is now, at the end of the last substep (rapier's narrow phase, which runs at
    /// the start of each substep, saw them one substep, 1/240 s, earlier).
    pub fn kinematic_collision(&mut self, robot: &Robot) -> Option<(Part, Part, f64)> {
        self.place(robot);
        self.shapes.collision_among(&self.kinematic_pairs)
    }

    /// Every penetrating pair of those [`FreeSpace::kinematic_collision`] checks, with the
    /// robot where it is now: `(part, part, depth [m])`.
    pub fn kinematic_penetrations(&self, robot: &Robot) -> Vec<(Part, Part, f64)> {
        let mut shapes = self.shapes.clone();
        place(&mut shapes, robot);
        shapes.penetrating_among(&self.kinematic_pairs)
    }

    fn place(&mut self, robot: &Robot) {
        place(&mut self.shapes, robot);
    }

    /// An upper bound on how far any point of the robot moved from `from` to `to` \[m\]: each
    /// joint's turn times its reach, plus the larger finger travel.
    fn motion_bound(&self, from: &MotionState, to: &MotionState) -> f64 {
        let arm: f64 = (0..6)
            .map(|i| (to.q[i] - from.q[i]).abs() * self.reach[i])
            .sum();
        let fingers = (0..2)
            .map(|f| (to.fingers[f].travel - from.fingers[f].travel).abs())
            .fold(0.0, f64::max);
        arm + fingers
    }
}

/// Places `shapes` where `robot` is: its joints and finger travels.
fn place(shapes: &mut RobotShapes, robot: &Robot) {
    let travel = robot.fingers.map(|f| f.travel);
    shapes.place(&robot.model, &robot.base, &robot.q, travel);
}

/// For each joint, an upper bound on the distance from its axis to any point it moves \[m\]: the
/// joint origins' spacing along the chain (fixed for any joint angles) plus the farthest point
/// of each moved link's capsule and of the gripper from its own frame's origin.
pub fn joint_reach(model: &ArmModel) -> [f64; 6] {
    let poses = model.link_poses(&[0.0; 6]);
    let origin = |i: usize| poses[i].translation.vector;
    let tool0 = model.fk_flange(&[0.0; 6]).iso.translation.vector;
    // Farthest capsule point from link j's origin.
    let extent = |j: usize| {
        model
            .capsules
            .iter()
            .filter(|c| c.link == model.links[j])
            .map(|c| {
                let norm = |p: [f64; 3]| nalgebra::Vector3::from(p).norm();
                norm(c.from).max(norm(c.to)) + c.radius
            })
            .fold(0.0, f64::max)
    };
    let g = &model.gripper;
    let gripper_extent = nalgebra::Vector3::new(
        (0.5 * g.palm_size[0]).max(g.finger_travel + g.pad_size[0] + 0.01),
        0.5 * g.palm_size[1].max(g.pad_size[1]),
        g.tcp_offset + 0.5 * g.pad_size[2],
    )
    .norm();
    std::array::from_fn(|i| {
        // Joint i turns links i+1 … 6 and the gripper about an axis through link i+1's origin.
        let mut along = 0.0;
        let mut reach = 0.0_f64;
        for j in i + 1..=6 {
            reach = reach.max(along + extent(j));
            along += if j < 6 {
                (origin(j + 1) - origin(j)).norm()
            } else {
                (tool0 - origin(6)).norm()
            };
        }
        reach.max(along + gripper_extent)
    })
}
