//! `fairgrasp tune`: a hand-written control's parameters tuned on training scenarios by an
//! optimiser, with a budget of env steps (by default the place residual's, about 3 M), so that
//! a learned policy is compared with the control at its best.
//!
//! - [`spec`]: what a tuning is ([`TuneSpec`]), checked; its record in `tune.json`;
//! - [`optimiser`]: the loop ([`run_tune`]: CMA-ES, resumable trial for trial, restarted when it
//!   stalls), then the best trials re-evaluated on validation scenarios and the best there
//!   chosen;
//! - [`trials`]: `trials.csv`, one row a trial;
//! - [`folder`]: claiming or resuming a tuning folder;
//! - [`fragment`]: the tuned setting as a preset fragment, written and read into a preset.
//!
//! Why CMA-ES (the `cmaes` crate): the objective is a success rate, noisy and without
//! gradients, over 2–8 bounded parameters, and a trial costs seconds, so a few hundred trials
//! is the whole budget: CMA-ES is the standard black-box optimiser for that size, needs no
//! model of the objective (Bayesian optimisation's Gaussian process fits noisy rates poorly at
//! this count), is seeded (a resumed tuning asks the same questions again) and is pure Rust.

pub mod error;
pub mod folder;
pub mod fragment;
pub mod optimiser;
pub mod spec;
pub mod trials;

pub use error::TuneError;
pub use optimiser::{Finalist, TuneEvent, TuneOutcome, best_of, chosen_of, finalists_of, run_tune};
pub use spec::{Objective, TuneSpec, Validation};
