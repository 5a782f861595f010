//! fairgrasp-bench: the measurements behind `fairgrasp bench`, kept out of the crates they
//! measure.
//!
//! - [`env`]: reset times and stepping throughput of the grasp env (`bench env`);
//! - [`soak`]: one env stepped for a long time, counting what must never happen (`bench soak`);
//! - [`ppo`]: PPO's update and training throughput (`bench ppo`).

pub mod env;
pub mod ppo;
pub mod soak;
