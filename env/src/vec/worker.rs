//! The worker threads of [`crate::vec::VecEnv`]: each owns a chunk of environments and
//! waits on a mutex and condition variable for a job (reset, step, new randomisation); a job
//! that panics marks the worker lost, and every later job fails with `EnvError::WorkerLost`.
//!
//! A free-space step takes about 10 µs, less than a sleeping thread takes to wake: so before
//! sleeping on the condition variable, a worker waiting for its next job and the caller waiting
//! for a job's end first spin for up to [`SPIN`] on an atomic flag. The mutex still guards every
//! datum and decides every hand-over; the flags only say when to look.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crate::config::RandomizationConfig;
use crate::env::EnvError;
use crate::vec::chunk::Chunk;

/// What a worker is asked to do, and its answer.
pub(crate) enum Job {
    Idle,
    Reset,
    Step,
    SetRandomization(RandomizationConfig),
    Finished(Result<(), EnvError>),
    Quit,
}

/// A worker's chunk and its job, behind one mutex.
pub(crate) struct Shared {
    pub(crate) chunk: Chunk,
    pub(crate) job: Job,
    /// A job panicked: the chunk may be half-stepped, every later job fails.
    pub(crate) lost: bool,
}

/// How long a waiting thread spins before it sleeps: a few free-space steps of a chunk.
pub(crate) const SPIN: Duration = Duration::from_micros(60);

/// A worker's chunk and job, its wake-up, and the two flags the waiting side spins on.
pub(crate) struct Mailbox {
    pub(crate) state: Mutex<Shared>,
    pub(crate) wake: Condvar,
    /// Set when a job is handed over, cleared when the worker takes it.
    posted: AtomicBool,
    /// Set when a job's result is in `Shared::job`, cleared when the caller takes it.
    done: AtomicBool,
}

/// Spins until `flag` is set or [`SPIN`] has passed.
fn spin_on(flag: &AtomicBool) {
    let start = Instant::now();
    let mut turns = 0u32;
    while !flag.load(Ordering::Acquire) {
        std::hint::spin_loop();
        turns = turns.wrapping_add(1);
        if turns.is_multiple_of(64) && start.elapsed() >= SPIN {
            return;
        }
    }
}

pub(crate) struct Worker {
    pub(crate) mailbox: Arc<Mailbox>,
    pub(crate) thread: Option<JoinHandle<()>>,
    pub(crate) len: usize,
}

pub(crate) fn run_job(shared: &mut Shared, job: Job) -> Result<(), EnvError> {
    if shared.lost {
        return Err(EnvError::WorkerLost);
    }
    let chunk = &mut shared.chunk;
    let result = catch_unwind(AssertUnwindSafe(|| match job {
        Job::Reset => chunk.reset(),
        Job::Step => chunk.step_own_actions(),
        Job::SetRandomization(r) => chunk.set_randomization(&r),
        Job::Idle | Job::Finished(_) | Job::Quit => Ok(()),
    }));
    result.unwrap_or_else(|_| {
        shared.lost = true;
        Err(EnvError::WorkerLost)
    })
}

pub(crate) fn worker_loop(mailbox: &Mailbox) {
    loop {
        spin_on(&mailbox.posted);
        let Ok(mut shared) = mailbox.state.lock() else {
            return;
        };
        // Jobs are taken under the lock; waiting there cannot miss a hand-over.
        while matches!(shared.job, Job::Idle | Job::Finished(_)) {
            shared = match mailbox.wake.wait(shared) {
                Ok(s) => s,
                Err(_) => return,
            };
        }
        mailbox.posted.store(false, Ordering::Release);
        match std::mem::replace(&mut shared.job, Job::Idle) {
            Job::Quit => return,
            job => {
                let result = run_job(&mut shared, job);
                shared.job = Job::Finished(result);
                mailbox.done.store(true, Ordering::Release);
                mailbox.wake.notify_all();
            }
        }
    }
}

pub(crate) fn spawn_worker(chunk: Chunk) -> Worker {
    let len = chunk.envs.len();
    let mailbox = Arc::new(Mailbox {
        state: Mutex::new(Shared {
            chunk,
            job: Job::Idle,
            lost: false,
        }),
        wake: Condvar::new(),
        posted: AtomicBool::new(false),
        done: AtomicBool::new(false),
    });
    let theirs = Arc::clone(&mailbox);
    let thread = std::thread::spawn(move || worker_loop(&theirs));
    Worker {
        mailbox,
        thread: Some(thread),
        len,
    }
}

impl Worker {
    pub(crate) fn lock(&self) -> Result<MutexGuard<'_, Shared>, EnvError> {
        self.mailbox.state.lock().map_err(|_| EnvError::WorkerLost)
    }

    /// Hands the worker a job (after `prepare` has filled its inputs).
    pub(crate) fn start(&self, job: Job, prepare: impl FnOnce(&mut Chunk)) -> Result<(), EnvError> {
        let mut shared = self.lock()?;
        prepare(&mut shared.chunk);
        shared.job = job;
        self.mailbox.posted.store(true, Ordering::Release);
        self.mailbox.wake.notify_all();
        Ok(())
    }

    /// Asks the worker to end (its thread returns after the current job).
    pub(crate) fn quit(&self) {
        if let Ok(mut shared) = self.mailbox.state.lock() {
            shared.job = Job::Quit;
            self.mailbox.posted.store(true, Ordering::Release);
            self.mailbox.wake.notify_all();
        }
    }

    /// Waits for the job's end; the guard gives access to the chunk's outcomes.
    pub(crate) fn finish(
        &self,
    ) -> Result<(MutexGuard<'_, Shared>, Result<(), EnvError>), EnvError> {
        spin_on(&self.mailbox.done);
        let mut shared = self.lock()?;
        loop {
            match std::mem::replace(&mut shared.job, Job::Idle) {
                Job::Finished(result) => {
                    self.mailbox.done.store(false, Ordering::Release);
                    return Ok((shared, result));
                }
                pending => {
                    shared.job = pending;
                    shared = self
                        .mailbox
                        .wake
                        .wait(shared)
                        .map_err(|_| EnvError::WorkerLost)?;
                }
            }
        }
    }
}
