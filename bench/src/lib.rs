//! fairgrasp-bench: the measurements behind `fairgrasp bench`, kept out of the crates they
//! measure.
//!
//! - [`env`]: reset times and stepping throughput of the grasp env (`bench env`);
//! - [`soak`]: one env stepped for a long time, counting what must never happen (`bench soak`);
//! - `ppo`: PPO's update and training throughput (`bench ppo`), with the `ppo` feature (it
//!   links the trainer, burn).

pub mod env;
#[cfg(feature = "ppo")]
pub mod ppo;
pub mod soak;
