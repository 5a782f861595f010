//! fairgrasp-types: the one schema of fairgrasp's result files, shared by the crates that
//! produce them (the environment's evaluation, the comparison experiment) and the report crate
//! that draws charts from them without any simulator.
//!
//! - [`names`]: the typed names written into result files ([`Outcome`], [`ArmSimulation`]).
//! - [`eval`]: one evaluated episode and an evaluation report ([`EvalReport`], Wilson interval).
//! - [`compare`]: a comparison of methods on presets (`compare.json`).
//! - [`paired`]: McNemar's exact test between two methods on the same scenarios.
//! - [`fs`]: [`write_atomic`], the one way fairgrasp writes a result file.

pub mod checksum;
pub mod compare;
pub mod eval;
pub mod fs;
pub mod names;
pub mod paired;

pub use compare::{Comparison, MethodResult, RecordedEpisode, SchemaError};
pub use eval::{EpisodeResult, EvalReport, wilson_interval};
pub use fs::write_atomic;
pub use names::{ArmSimulation, Outcome, UnknownName};
pub use paired::{PairedTest, PairingError, learned_vs_scripts, mcnemar_exact, paired_test};
