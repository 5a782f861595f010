//! The environment benchmark (`fairgrasp bench env`): soft and hard reset times on one env, and
//! stepping throughput of a [`VecEnv`] under random actions with auto-reset.

use std::time::Instant;

use fairgrasp_types::ArmSimulation;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use fairgrasp_env::vec::VecEnv;
use fairgrasp_env::{Action, EnvConfig, EnvError, TaskEnv};

/// What to measure.
#[derive(Clone, Debug)]
pub struct EnvBenchSpec {
    /// The environment (its `arm.model` and `physics` are used as given).
    pub config: EnvConfig,
    /// Threads stepping environments in parallel.
    pub threads: usize,
    /// Environments per thread.
    pub envs_per_thread: usize,
    /// Steps of each environment.
    pub steps: usize,
    /// Resets timed for each of soft and hard reset (seeds `0..resets`).
    pub resets: usize,
}

/// What was measured. Rates are per second of wall-clock or CPU time.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnvBenchReport {
    pub arm: ArmSimulation,
    pub threads: usize,
    /// Environments stepped (`threads × envs_per_thread`).
    pub envs: usize,
    /// Environment steps done in the throughput phase (all envs).
    pub env_steps: f64,
    /// Episodes that ended (and were auto-reset) during the throughput phase.
    pub episodes_ended: usize,
    /// Share of the throughput phase's env steps that ran rigid-body physics (the rest were
    /// free-space steps, see `physics.free_space`), in [0, 1].
    pub simulated_share: f64,
    /// Physics steps per environment step (the config's substeps).
    pub substeps: usize,
    /// Physics time step \[s\].
    pub dt: f64,
    /// Wall-clock time of the throughput phase \[s\].
    pub wall_s: f64,
    /// CPU time of this process (all threads) during the throughput phase \[s\].
    pub cpu_s: f64,
    pub env_steps_per_s: f64,
    pub env_steps_per_cpu_s: f64,
    /// Physics steps actually run per second (free-space env steps run none).
    pub physics_steps_per_s: f64,
    /// Mean soft reset time \[ms\].
    pub soft_reset_ms: f64,
    /// Mean hard reset (world rebuilt from nothing) time \[ms\].
    pub hard_reset_ms: f64,
    /// Fastest soft reset \[ms\].
    pub soft_reset_min_ms: f64,
    /// Fastest hard reset \[ms\].
    pub hard_reset_min_ms: f64,
}

/// Why the benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum EnvBenchError {
    #[error(
        "bench env: threads ({threads}), envs per thread ({envs_per_thread}), steps ({steps}) and resets ({resets}) must all be at least 1"
    )]
    Empty {
        threads: usize,
        envs_per_thread: usize,
        steps: usize,
        resets: usize,
    },
    #[error(transparent)]
    Env(#[from] EnvError),
}

/// CPU time used by this process so far \[s\] (user + system, all threads).
fn cpu_seconds() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes a complete rusage into the pointer it is given; on failure the
    // zeroed value stays, which is also a valid rusage.
    let usage = unsafe {
        libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr());
        usage.assume_init()
    };
    let tv = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    tv(usage.ru_utime) + tv(usage.ru_stime)
}

/// Runs `f` for seeds `0..n`, timing each call: (mean, minimum) \[ms\]. The minimum is what the
/// work costs without the scheduler's interruptions.
fn time_each(
    n: usize,
    mut f: impl FnMut(u64) -> Result<(), EnvError>,
) -> Result<(f64, f64), EnvError> {
    let (mut total, mut min) = (0.0, f64::INFINITY);
    for seed in 0..n as u64 {
        let t = Instant::now();
        f(seed)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        total += ms;
        min = min.min(ms);
    }
    Ok((total / n as f64, min))
}

/// Runs the benchmark; `before_stepping` is called once between the reset and the throughput
/// phases (the CLI prints what it is about to step).
pub fn bench_env(
    spec: &EnvBenchSpec,
    before_stepping: &dyn Fn(),
) -> Result<EnvBenchReport, EnvBenchError> {
    if spec.threads == 0 || spec.envs_per_thread == 0 || spec.steps == 0 || spec.resets == 0 {
        return Err(EnvBenchError::Empty {
            threads: spec.threads,
            envs_per_thread: spec.envs_per_thread,
            steps: spec.steps,
            resets: spec.resets,
        });
    }
    let config = &spec.config;
    let mut env = TaskEnv::new(config.clone())?;
    // One untimed reset first: the first one pays for cold caches and allocations, which would
    // otherwise be charged to the soft reset alone.
    env.reset(0)?;
    let (soft_reset_ms, soft_reset_min_ms) =
        time_each(spec.resets, |seed| env.reset(seed).map(|_| ()))?;
    let (hard_reset_ms, hard_reset_min_ms) =
        time_each(spec.resets, |seed| env.hard_reset(seed).map(|_| ()))?;

    let envs = spec.threads * spec.envs_per_thread;
    let mut vec_env = VecEnv::new(config, envs, spec.threads, 0)?;
    vec_env.reset()?;
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let actions: Vec<Vec<Action>> = (0..256)
        .map(|_| {
            (0..envs)
                .map(|_| Action(std::array::from_fn(|_| rng.random_range(-1.0..1.0))))
                .collect()
        })
        .collect();
    before_stepping();
    let mut episodes_ended = 0;
    let mut simulated = 0;
    let (cpu0, t) = (cpu_seconds(), Instant::now());
    for k in 0..spec.steps {
        let step = vec_env.step(&actions[k % actions.len()])?;
        episodes_ended += step
            .terminated
            .iter()
            .zip(&step.truncated)
            .filter(|(a, b)| **a || **b)
            .count();
        simulated += step.infos.iter().filter(|i| i.simulated).count();
    }
    let wall_s = t.elapsed().as_secs_f64();
    let cpu_s = cpu_seconds() - cpu0;
    let env_steps = (spec.steps * envs) as f64;
    let substeps = config.physics.substeps;
    Ok(EnvBenchReport {
        arm: config.arm.model,
        threads: spec.threads,
        envs,
        env_steps,
        episodes_ended,
        simulated_share: simulated as f64 / env_steps,
        substeps,
        dt: config.physics.dt,
        wall_s,
        cpu_s,
        env_steps_per_s: env_steps / wall_s,
        env_steps_per_cpu_s: env_steps / cpu_s.max(1e-9),
        physics_steps_per_s: simulated as f64 * substeps as f64 / wall_s,
        soft_reset_ms,
        hard_reset_ms,
        soft_reset_min_ms,
        hard_reset_min_ms,
    })
}
