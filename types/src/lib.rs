//! fairgrasp-types: the one schema of fairgrasp's result files, shared by the crates that
//! produce them (the environment's evaluation, the comparison experiment) and the report crate
//! that draws charts from them without any simulator.
//!
//! - [`names`]: the typed names written into result files ([`Outcome`], [`ArmSimulation`]).
//! - [`episode`]: the one record of a finished episode and how its outcome is decided.
//! - [`eval_report`]: an evaluation report over episodes ([`EvalReport`], Wilson interval).
//! - [`comparison`]: a comparison of methods on presets (`compare.json`).
//! - [`paired`]: McNemar's exact test between two methods on the same scenarios.
//! - [`trajectory`]: one recorded episode (written by the env, read by the report); [`body`]:
//!   the robot's bodies and shapes in it, for 3D replays.
//! - [`fs`]: [`write_atomic`], the one way fairgrasp writes a result file; [`output`]: when an
//!   existing file may be written over (only one fairgrasp wrote).
//! - [`text`]: line numbers of offsets (LF, CRLF and CR files) and bounded excerpts of input
//!   for messages.
//! - [`work_queue`]: numbered jobs shared by worker threads, results in job order.
//! - [`checksum`]: 64-bit FNV-1a, the checksum of checkpoints and report folders.

pub mod body;
pub mod checksum;
pub mod comparison;
pub mod episode;
pub mod eval_report;
pub mod fs;
pub mod names;
pub mod output;
pub mod paired;
pub mod text;
pub mod trajectory;
pub mod work_queue;

pub use comparison::{Comparison, ControlTuning, MethodResult, RecordedEpisode, SchemaError};
pub use episode::{EpisodeFacts, EpisodeRecord};
pub use eval_report::{EvalReport, wilson_interval};
pub use fs::{read_bounded, read_text_bounded, write_atomic};
pub use names::{ArmSimulation, Outcome, UnknownName};
pub use paired::{
    PairedTest, PairingError, best_script, learned_vs_key_scripts, learned_vs_scripts,
    mcnemar_exact, paired_test, sees_the_truth,
};
