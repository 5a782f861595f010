//! Fault injection for the kill tests (`tests/kill_resume.rs`), compiled only with the cargo
//! feature `crash-injection` (which the root package's tests enable through a dev-dependency):
//! a binary built for users has no such hook, and these functions do nothing in it.
//!
//! With the feature, when the environment variable `FAIRGRASP_CRASH_AT` equals `POINT@UPDATE`
//! (e.g. `before_row@2`), the process aborts at that point of that update, as a kill would (no
//! destructors, no flushing).

/// Aborts the process if `FAIRGRASP_CRASH_AT` asks for a crash at `point` of `update`.
pub fn point(point: &str, update: u64) {
    if requested(point, update) {
        std::process::abort();
    }
}

/// Whether `FAIRGRASP_CRASH_AT` asks for a crash at `point` of `update` (always false without
/// the `crash-injection` feature).
pub fn requested(point: &str, update: u64) -> bool {
    cfg!(feature = "crash-injection")
        && std::env::var("FAIRGRASP_CRASH_AT").is_ok_and(|t| t == format!("{point}@{update}"))
}

/// If `FAIRGRASP_CRASH_AT` asks for a crash at `point` of `update`: writes the first half of
/// `bytes` to `out` (a kill in the middle of a write) and aborts.
pub fn torn_write(point: &str, update: u64, out: &mut impl std::io::Write, bytes: &[u8]) {
    if requested(point, update) {
        let _ = out.write_all(&bytes[..bytes.len() / 2]);
        std::process::abort();
    }
}
