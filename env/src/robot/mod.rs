//! The robot: the FR3 arm (servo or multibody) and its force-limited parallel gripper. It applies
//! an action and reports joint and gripper state; the simulator is reached only through
//! [`Sim`](crate::sim::Sim).
//!
//! Both arm models share one rate limiter: the commanded joint velocity is clamped to the FR3
//! velocity limits and reached with at most `max_acceleration`. The servo arm integrates it and
//! places kinematic links by FK; the multibody arm hands it to the joint position motors.

pub mod arm_and_gripper;
pub mod tcp_action;

pub use arm_and_gripper::*;
