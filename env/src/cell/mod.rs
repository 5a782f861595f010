//! The cell: which arm ([`arm`]), where it stands ([`mount`]: its base and the table frame in
//! the world), and how it is simulated — derived once from a config ([`derived::Cell`]).
//!
//! `arm` and `mount` are frame arithmetic; `derived` reads the config. The config does not
//! import the cell: it checks the base's tilt and the home joints itself
//! ([`crate::config::validate::base_tilt`], [`crate::config::SIMULATED_ARM`]).

pub mod arm;
pub mod derived;
pub mod mount;

pub use arm::arm_model;
pub use derived::Cell;
pub use mount::Mount;
