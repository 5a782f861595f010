//! fairgrasp-kinematics: the FAIRINO FR3 (and FR5) as numbers and as maths.
//!
//! - [`fairino`]: FAIRINO's published DH table, limits, masses and collision capsules;
//!   [`model::ArmModel`] says what each number means.
//! - [`pose`]: rigid poses, RPY/quaternion conversions, `world_to_base` / `base_to_world`.
//! - [`fk`]: closed-form DH forward kinematics, geometric Jacobian, manipulability.
//! - [`urdf`]: any serial URDF: joint table, chain to a tip link, FK; errors name the culprit.
//! - [`analytic_ik`]: all (up to 8) closed-form IK branches, wrapped into the joint limits.
//! - [`diff_ik`] and [`qp_ik`]: differential IK as one clarabel QP, and an iterative solver.
//!
//! Frames follow ROS: `world`, `base_link`, `tool0` (the flange, DH frame 6) and `tcp` (between
//! the finger pads, 0.14 m along `tool0` z). Lengths are metres, angles radians.

pub mod analytic_ik;
pub mod diff_ik;
pub mod fairino;
pub mod fk;
pub mod model;
pub mod pose;
pub mod qp_ik;
pub mod urdf;
mod urdf_check;

pub use analytic_ik::{AnalyticIkOptions, IkError, IkSolution, nearest_solution};
pub use fk::{EndFrame, manipulability, min_singular_value};
pub use model::{ArmKind, ArmModel};
pub use pose::{Pose, base_to_world, world_to_base};
pub use qp_ik::{QpIkError, QpIkOptions, QpIkSolution};
pub use urdf::{SerialChain, UrdfError, UrdfRobot};

/// The FR3 URDF shipped in `assets/fr3.urdf` (arm, flange, parallel gripper, TCP).
pub const FR3_URDF: &str = include_str!("../../assets/fr3.urdf");
/// The FR5 URDF shipped in `assets/fr5.urdf` (arm and flange).
pub const FR5_URDF: &str = include_str!("../../assets/fr5.urdf");
