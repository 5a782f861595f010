//! fairgrasp-bench: the measurements behind `fairgrasp bench`, kept out of the crates they
//! measure.
//!
//! - [`mod@env`]: reset times and stepping throughput of the grasp env (`bench env`);
//! - [`ik`]: the chain IK on random reachable poses beside the FR3's closed form (`bench ik`);
//! - [`soak`]: one env stepped for a long time, counting what must never happen (`bench soak`);
//! - `ppo`: PPO's update and training throughput (`bench ppo`), with the `ppo` feature (it
//!   links the trainer, burn).

pub mod env;
pub mod ik;
#[cfg(feature = "ppo")]
pub mod ppo;
pub mod soak;
