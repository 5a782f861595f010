//! Per-episode scenarios: object position, yaw, friction, mass and joint noise, drawn from a seed,
//! each one checked to admit a top-down grasp within the FR3's joint limits.

pub mod curriculum;
pub mod families;
pub mod fixture;
pub mod graspable;
pub mod grip_tilt;
pub mod noise;
pub mod nudge;
pub mod perception;
pub mod sample;

pub use graspable::*;
pub use sample::*;
