//! fairgrasp-evaluate: the methods — the scripts and the policies of `fairgrasp-policy` — run on
//! seeded scenario sets, without burn.
//!
//! - [`compare`]: every method on the same scenario sets (the `compare` experiment).
//! - [`squeeze_probe`]: the grip force a squeezing residual commands against the squeeze each
//!   cube needed (`fairgrasp eval --squeeze-chart`).
//! - [`export`]: one episode as a servo stream for a real FR3 (`fairgrasp export`).
//! - [`tune`]: a hand-written control's parameters tuned on training scenarios by CMA-ES
//!   (`fairgrasp tune`).
//! - [`wrench_probe`]: what the six-axis wrist sensor tells at a place cycle's first touch,
//!   against the truth (`fairgrasp wrench-probe`).

pub mod compare;
pub mod export;
pub mod squeeze_probe;
pub mod tune;
pub mod wrench_probe;
