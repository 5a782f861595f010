//! The six-axis wrist force/torque sensor between the flange and the gripper: what it reads
//! ([`wrench`]: the wrench type, the centre of pressure, a change of frame; the simulator's
//! contacts give the true wrench, `crate::sim::contacts::wrist_wrench`) and how a real sensor's
//! reading differs from the truth ([`reading`]: noise and resolution, `[sensor.wrench]`).
//!
//! May import `config` and `kinematics`; imported by `sim` (the wrench type), `env` (the
//! observation) and the planner's controls.

pub mod reading;
pub mod wrench;

pub use reading::read_with_noise;
pub use wrench::Wrench;
