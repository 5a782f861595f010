//! The URDF reader: text or file → checked joint table ([`UrdfRobot`]) → a serial chain to a tip
//! link ([`SerialChain`]) with forward kinematics.
//!
//! What lives here: the first pass over the XML that names the offending line (`check.rs`), the
//! second that reads links and joints out of it (`read.rs`), the errors (`error.rs`), the joint
//! (`joint.rs`), the tree and its checks (`robot.rs`) and the chain (`chain.rs`). It builds only on [`crate::pose`]; anything in the crate above it (the
//! IK for serial chains) and any other crate may import it, through the names re-exported here.

mod chain;
mod check;
mod error;
mod joint;
mod read;
mod robot;

pub use chain::SerialChain;
pub use check::{MAX_NESTING_DEPTH, MAX_URDF_BYTES};
pub use error::UrdfError;
pub use joint::{JointKind, UrdfJoint};
pub use robot::UrdfRobot;
