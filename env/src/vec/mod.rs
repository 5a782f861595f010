//! N environments stepped in parallel threads, with auto-reset and batched, typed observations.
//!
//! The environments are split into one chunk per thread; the calling thread steps the first
//! chunk and persistent worker threads the others (spawning threads every step costs more than a
//! step here). Environment `i` draws the seed of its `k`-th episode as
//! `base_seed + i · 1 000 000 + k`, so a run is reproducible whatever the number of threads.
//!
//! The batch holds the environments' own [`Observation`](crate::Observation)s (f64, `base_link`),
//! not a flattened copy: a policy reads exactly what a single [`TaskEnv`](crate::TaskEnv) would
//! have handed it.
//!
//! A step allocates nothing of its own once every buffer has reached its size (after the first
//! reset and step): the actions handed to a worker, a chunk's outcomes and the batch handed back
//! are cleared and refilled in place, and a worker is woken through a mutex and a condition
//! variable rather than a channel (whose queue allocates as messages flow). What the environments
//! allocate inside their own `step`/`reset` is theirs.

pub(crate) mod chunk;
pub mod vec_env;
pub(crate) mod worker;

pub use chunk::VecStep;
pub use vec_env::*;
