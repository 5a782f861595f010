//! fairgrasp-kinematics: the FAIRINO FR3 (and FR5) as numbers and as maths.
//!
//! - [`fairino`]: FAIRINO's published DH table, limits, masses and collision capsules;
//!   [`model::ArmModel`] says what each number means.
//! - [`pose`]: rigid poses, RPY/quaternion conversions, `world_to_base` / `base_to_world`.
//! - [`fk`]: closed-form DH forward kinematics, geometric Jacobian, manipulability.
//! - [`geometry`]: exact segment–box and box–box distances and penetration depths.
//! - [`urdf`]: any serial URDF: joint table, chain to a tip link, FK; errors name the culprit.
//! - [`calibrate`]: the base's mount and a fixed camera's pose from measurements in a cell.
//! - [`analytic_ik`]: all (up to 8) closed-form IK branches, wrapped into the joint limits.
//! - [`diff_ik`] and [`qp_ik`]: differential IK as one clarabel QP, and an iterative solver.
//! - [`chain_ik`]: IK for any serial URDF chain (damped QP steps, seeded restarts).
//! - [`collision`]: self-collision and clearance checks on the arm's and gripper's capsules.
//! - [`angles`]: the angle arithmetic the IK solvers share.
//!
//! Frames follow ROS: `world`, `base_link`, `tool0` (the flange, DH frame 6) and `tcp` (between
//! the finger pads, 0.14 m along `tool0` z). Lengths are metres, angles radians.
//!
//! ```
//! use fairgrasp_kinematics::{AnalyticIkOptions, ArmKind, EndFrame, FR3_URDF, Pose, UrdfRobot};
//!
//! // Load the URDF, list its joints, and build the chain to the TCP.
//! let robot = UrdfRobot::from_str_named(FR3_URDF, "fr3.urdf").unwrap();
//! assert_eq!(robot.movable_joints().count(), 8); // six arm joints, two fingers
//! let chain = robot.chain(Some("tcp")).unwrap();
//!
//! // Forward kinematics two ways: the DH model and the URDF chain agree.
//! let fr3 = ArmKind::Fr3.model();
//! let q = [0.3, -1.2, 1.1, -1.4, 0.8, 0.5];
//! let (dp, dr) = fr3.fk_tcp(&q).distance_to(&chain.fk(&q));
//! assert!(dp < 1e-9 && dr < 1e-9);
//!
//! // A top-down grasp 0.35 m in front of the base: every IK branch, then the nearest one.
//! let grasp = Pose::from_xyz_rpy([0.35, 0.0, 0.05], [std::f64::consts::PI, 0.0, 0.0]);
//! let branches = fr3.ik_analytic(&grasp, EndFrame::Tcp, &AnalyticIkOptions::default()).unwrap();
//! let best = fr3.ik_nearest(&grasp, EndFrame::Tcp, &q).unwrap().expect("an in-limit branch");
//! assert!(branches.len() <= 8 && best.in_limits);
//! assert!(fr3.fk_tcp(&best.joints).distance_to(&grasp).0 < 1e-9);
//! ```

pub mod analytic_ik;
pub mod angles;
pub mod calibrate;
pub mod chain_ik;
pub mod collision;
pub mod diff_ik;
pub mod fairino;
pub mod fk;
pub mod geometry;
pub mod model;
pub mod pose;
pub mod qp_ik;
mod restart;
pub mod urdf;
mod wrist_singular;

pub use analytic_ik::{AnalyticIkOptions, IkError, IkSolution, nearest_solution};
pub use fk::{EndFrame, damped_least_squares, manipulability, min_singular_value};
pub use model::{ArmKind, ArmModel};
pub use pose::{Pose, base_to_world, world_to_base};
pub use qp_ik::{QpIkError, QpIkOptions, QpIkSolution};
pub use urdf::{JointKind, SerialChain, UrdfError, UrdfRobot};

/// The FR3 URDF shipped in `assets/fr3.urdf` (arm, flange, parallel gripper, TCP).
pub const FR3_URDF: &str = include_str!("../../assets/fr3.urdf");
/// The FR5 URDF shipped in `assets/fr5.urdf` (arm and flange).
pub const FR5_URDF: &str = include_str!("../../assets/fr5.urdf");
/// A 7-joint arm fairgrasp writes for its IK tests and benchmarks (`assets/seven_joint_arm.urdf`;
/// no real product).
pub const SEVEN_JOINT_URDF: &str = include_str!("../../assets/seven_joint_arm.urdf");
