//! The cell: which arm ([`arm`]), where it stands ([`mount`]: its base and the table frame in
//! the world), and how it is simulated — derived once from a config ([`derived::Cell`]).
//!
//! `arm` and `mount` are frame arithmetic that needs no config (the config's checks use them);
//! `derived` reads the config.

pub mod arm;
pub mod derived;
pub mod mount;

pub use arm::arm_model;
pub use derived::Cell;
pub use mount::Mount;
