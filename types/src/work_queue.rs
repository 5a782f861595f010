//! One queue of numbered jobs shared by worker threads: each worker claims the next job number
//! when it is free, so no worker idles while another still has a long share (as with fixed
//! chunks, one per thread). Used for `compare`'s episodes and recordings and the report's charts.
//!
//! The rules, the same for every user: jobs are claimed in number order; results come back in
//! number order; after a job fails no further job is claimed, and the error returned is the one
//! of the lowest-numbered failing job (the same error however the threads interleaved); a panic
//! in a job stops the others from claiming, then reaches the caller.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// Sets `stop` if the thread unwinds from a panic while this guard lives.
struct StopOnPanic<'a>(&'a AtomicBool);

impl Drop for StopOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.store(true, Ordering::Relaxed);
        }
    }
}

/// Runs `run(state, j)` for every job `j` in `0..jobs` on `threads` threads (at least one, at
/// most one per job). Each thread makes its own `state` with `new_state` (an env, a policy: it
/// never leaves the thread) and reuses it for every job it claims. `on_claim(j)` is called as
/// job `j` is claimed, under the queue's lock, so its calls come in job order.
pub fn run_in_order<S, T, E>(
    jobs: usize,
    threads: usize,
    on_claim: &(dyn Fn(usize) + Sync),
    new_state: &(dyn Fn() -> S + Sync),
    run: &(dyn Fn(&mut S, usize) -> Result<T, E> + Sync),
) -> Result<Vec<T>, E>
where
    T: Send,
    E: Send,
{
    let next = Mutex::new(0usize);
    let stop = AtomicBool::new(false);
    let claim = || -> Option<usize> {
        let mut next = next.lock().unwrap_or_else(|p| p.into_inner());
        if *next >= jobs || stop.load(Ordering::Relaxed) {
            return None;
        }
        let j = *next;
        *next += 1;
        on_claim(j);
        Some(j)
    };
    let worker = || -> Vec<(usize, Result<T, E>)> {
        let _guard = StopOnPanic(&stop);
        let mut state = new_state();
        let mut done = Vec::new();
        while let Some(j) = claim() {
            let result = run(&mut state, j);
            if result.is_err() {
                stop.store(true, Ordering::Relaxed);
            }
            done.push((j, result));
        }
        done
    };
    let mut all: Vec<(usize, Result<T, E>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads.clamp(1, jobs.max(1)))
            .map(|_| scope.spawn(worker))
            .collect();
        let mut all = Vec::with_capacity(jobs);
        for h in handles {
            match h.join() {
                Ok(done) => all.extend(done),
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
        all
    });
    all.sort_by_key(|(j, _)| *j);
    all.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn results_come_back_in_job_order_and_claims_are_announced_in_order() {
        let claimed = Mutex::new(Vec::new());
        let out: Result<Vec<usize>, ()> = run_in_order(
            50,
            3,
            &|j| claimed.lock().unwrap().push(j),
            &|| 0usize,
            &|count, j| {
                *count += 1;
                Ok(j * j)
            },
        );
        assert_eq!(out.unwrap(), (0..50).map(|j| j * j).collect::<Vec<_>>());
        assert_eq!(*claimed.lock().unwrap(), (0..50).collect::<Vec<_>>());
    }

    #[test]
    fn the_lowest_failing_job_is_reported_and_claiming_stops() {
        let failing = |_: &mut (), j: usize| if j == 7 || j == 9 { Err(j) } else { Ok(()) };
        // Two threads: job 7 is always claimed before job 9, so it always runs; its error is
        // the one reported whether or not job 9 ran too.
        let out: Result<Vec<()>, usize> = run_in_order(1000, 2, &|_| {}, &|| (), &failing);
        assert_eq!(out.unwrap_err(), 7);
        // One thread: nothing is claimed after the failure.
        let claimed = AtomicUsize::new(0);
        let on_claim = |_| {
            claimed.fetch_add(1, Ordering::Relaxed);
        };
        let out: Result<Vec<()>, usize> = run_in_order(1000, 1, &on_claim, &|| (), &failing);
        assert_eq!(out.unwrap_err(), 7);
        assert_eq!(
            claimed.load(Ordering::Relaxed),
            8,
            "jobs 0-7 claimed, then none"
        );
    }
}
