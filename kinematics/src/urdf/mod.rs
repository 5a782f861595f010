//! The URDF reader: text or file → checked joint table ([`UrdfRobot`]) → a serial chain to a tip
//! link ([`SerialChain`]) with forward kinematics.
//!
//! What lives here: the pre-check over the XML that names the offending line (`check.rs`, its
//! joint rules in `check_joint.rs`); urdf-rs, which reads the text; the search for the line of
//! what urdf-rs still refuses (`locate.rs`); the mapping of urdf-rs's robot into fairgrasp's
//! model (`map.rs`); the errors (`error.rs`), the joint (`joint.rs`), the tree and its checks
//! (`robot.rs`), the chain (`chain.rs`) and the one reader of an XML attribute both the pre-check
//! and the line search use (`xml.rs`). It builds only on [`crate::pose`]; anything in the
//! crate above it (the IK for serial chains) and any other crate may import it, through the
//! names re-exported here (urdf-rs among them, so that a caller's `urdf_rs::Robot` is the one
//! [`UrdfRobot::from_urdf_rs`] takes).

mod chain;
mod check;
mod check_joint;
mod error;
mod joint;
mod locate;
mod map;
mod robot;
mod xml;

pub use chain::SerialChain;
pub use check::{MAX_NESTING_DEPTH, MAX_URDF_BYTES};
pub use error::UrdfError;
pub use joint::{JointKind, UrdfJoint};
pub use robot::UrdfRobot;
pub use urdf_rs;
