//! Checkpoints as they are read after training: `meta.json` (sizes, configs, observation
//! statistics, progress) checked against the rules, and the weights of `model.bpk` verified
//! against its checksum and run as a plain-array [`crate::actor::Actor`], without burn.
//! Writing checkpoints (and loading them into burn to train on) is `fairgrasp-rl`'s
//! `run::checkpoint`.
//!
//! A checkpoint folder holds the network (`model.bpk`, burnpack), the optimiser state
//! (`optimizer.bpk`) and `meta.json`. A loader that finds no `meta.json` in `NAME` falls back to
//! `NAME.old` (a save interrupted between its two renames).
//!
//! Trusted only when it checks out: `meta.json` carries a checksum of `model.bpk` (and of
//! `optimizer.bpk`) taken together with the network's shape (mode, input size, hidden sizes), so
//! a flipped byte in the weights or an edited shape in the metadata is refused by name.
//!
//! - [`meta`]: `meta.json` ([`CheckpointMeta`]); [`network`]: the network's shape and its rule;
//!   [`normalizer`]: the observation statistics; [`verify`]: the ranges of `meta.json`'s numbers
//!   and the checksum over the folder's files; [`load`]: reading a folder into a policy;
//!   [`error`]: what a refused checkpoint says.

pub mod error;
pub mod load;
pub mod meta;
pub mod network;
pub mod normalizer;
pub mod verify;

pub use error::{CheckpointError, err};
pub use load::{actor_policy, existing, load_actor, load_meta, verified_model_bytes};
pub use meta::{CHECKPOINT_VERSION, CheckpointMeta, checksum};
