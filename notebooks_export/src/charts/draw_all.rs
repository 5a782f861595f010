//! Drawing a report's charts at once: PNG and GIF encoding are most of a report's time, and
//! every chart is its own file, so they are drawn on one thread per core, each thread claiming
//! the next chart not yet drawn. The files are the same as drawn one after another.

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::error::ReportError;

/// One chart to draw (it writes its own file).
pub(crate) type Drawing<'a> = Box<dyn Fn() -> Result<(), ReportError> + Send + Sync + 'a>;

/// Draws every drawing; on failure, returns the error of the first failing one in list order
/// (the same error whatever the threads did), after the others have stopped.
pub(crate) fn draw_all(drawings: &[Drawing<'_>]) -> Result<(), ReportError> {
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(drawings.len())
        .max(1);
    let next = AtomicUsize::new(0);
    let failed = AtomicUsize::new(usize::MAX);
    let mut errors: Vec<(usize, ReportError)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut errors = Vec::new();
                    loop {
                        let j = next.fetch_add(1, Ordering::Relaxed);
                        if j >= drawings.len() || j > failed.load(Ordering::Relaxed) {
                            return errors;
                        }
                        if let Err(e) = drawings[j]() {
                            failed.fetch_min(j, Ordering::Relaxed);
                            errors.push((j, e));
                        }
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a chart-drawing thread panicked"))
            .collect()
    });
    errors.sort_by_key(|(j, _)| *j);
    match errors.into_iter().next() {
        Some((_, e)) => Err(e),
        None => Ok(()),
    }
}
