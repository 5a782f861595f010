//! The worker threads of [`crate::vec::VecEnv`]: each owns a chunk of environments and
//! waits on a mutex and condition variable for a job (reset, step, new randomisation); a job
//! that panics marks the worker lost, and every later job fails with `EnvError::WorkerLost`.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;

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

pub(crate) type Mailbox = Arc<(Mutex<Shared>, Condvar)>;

pub(crate) struct Worker {
    pub(crate) mailbox: Mailbox,
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
    let (lock, wake) = &**mailbox;
    let Ok(mut shared) = lock.lock() else {
        return;
    };
    loop {
        match std::mem::replace(&mut shared.job, Job::Idle) {
            Job::Quit => return,
            waiting @ (Job::Idle | Job::Finished(_)) => {
                shared.job = waiting;
                shared = match wake.wait(shared) {
                    Ok(s) => s,
                    Err(_) => return,
                };
            }
            job => {
                let result = run_job(&mut shared, job);
                shared.job = Job::Finished(result);
                wake.notify_all();
            }
        }
    }
}

pub(crate) fn spawn_worker(chunk: Chunk) -> Worker {
    let len = chunk.envs.len();
    let mailbox: Mailbox = Arc::new((
        Mutex::new(Shared {
            chunk,
            job: Job::Idle,
            lost: false,
        }),
        Condvar::new(),
    ));
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
        self.mailbox.0.lock().map_err(|_| EnvError::WorkerLost)
    }

    /// Hands the worker a job (after `prepare` has filled its inputs).
    pub(crate) fn start(&self, job: Job, prepare: impl FnOnce(&mut Chunk)) -> Result<(), EnvError> {
        let mut shared = self.lock()?;
        prepare(&mut shared.chunk);
        shared.job = job;
        self.mailbox.1.notify_all();
        Ok(())
    }

    /// Waits for the job's end; the guard gives access to the chunk's outcomes.
    pub(crate) fn finish(
        &self,
    ) -> Result<(MutexGuard<'_, Shared>, Result<(), EnvError>), EnvError> {
        let mut shared = self.lock()?;
        loop {
            match std::mem::replace(&mut shared.job, Job::Idle) {
                Job::Finished(result) => return Ok((shared, result)),
                pending => {
                    shared.job = pending;
                    shared = self
                        .mailbox
                        .1
                        .wait(shared)
                        .map_err(|_| EnvError::WorkerLost)?;
                }
            }
        }
    }
}
