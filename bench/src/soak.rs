//! The soak: one env stepped for a long time by a policy plus seeded uniform noise (or by noise
//! alone), counting what must never happen (a non-finite observation or reward, an env error) and sampling the
//! process's resident memory, so a leak or a slow drift shows as a rising figure.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use fairgrasp_env::episode::Policy;
use fairgrasp_env::{Action, EnvConfig, EnvError, Observation, TaskEnv};

/// A policy that always says 0: with noise 1 the soak's actions are uniform in [−1, 1]⁷.
pub struct ZeroActions;

impl Policy for ZeroActions {
    fn reset(&mut self, _seed: u64) {}
    fn act(&mut self, _obs: &Observation) -> Action {
        Action([0.0; 7])
    }
}

/// What a soak saw.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SoakReport {
    /// Env steps taken.
    pub steps: u64,
    /// Steps that ran rigid-body physics (the rest were free-space steps).
    pub physics_steps: u64,
    /// Episodes ended (terminated or truncated) and reset.
    pub episodes: u64,
    /// Successful episodes (random actions: expect almost none).
    pub successes: u64,
    /// Steps whose observation held a NaN or infinity.
    pub non_finite_observations: u64,
    /// Steps whose reward was NaN or infinite.
    pub non_finite_rewards: u64,
    /// Episodes ended by a physics fault (a non-finite physics state, reported as truncated).
    pub physics_faults: u64,
    /// Errors returned by `reset` or `step` (the env was reset after each), and the first one.
    pub env_errors: u64,
    pub first_error: Option<String>,
    /// Resident memory after the first 10 % of the steps, and at the end \[KiB\] (0 where
    /// `/proc/self/statm` cannot be read). The process's, so soaks running side by side share
    /// it.
    pub rss_after_warmup_kib: u64,
    pub rss_end_kib: u64,
}

impl SoakReport {
    /// Nothing that must never happen happened: no non-finite observation or reward, no physics
    /// fault, no env error (`fairgrasp bench soak` exits 1 otherwise).
    pub fn is_clean(&self) -> bool {
        self.non_finite_observations == 0
            && self.non_finite_rewards == 0
            && self.physics_faults == 0
            && self.env_errors == 0
    }
}

/// The process's resident set size \[KiB\] from `/proc/self/statm` (Linux), 0 elsewhere.
pub fn resident_kib() -> u64 {
    let Ok(text) = std::fs::read_to_string("/proc/self/statm") else {
        return 0;
    };
    let pages: u64 = text
        .split_whitespace()
        .nth(1)
        .and_then(|p| p.parse().ok())
        .unwrap_or(0);
    // SAFETY: sysconf has no preconditions; it returns −1 on error.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    pages * u64::try_from(page).unwrap_or(4096) / 1024
}

/// Steps one env of `config` for `steps` steps with `policy`'s action plus uniform noise in
/// [−`noise`, `noise`]⁷ drawn from `seed`, clipped to [−1, 1]; episode `k` starts from scenario
/// seed `seed + k`. `progress` is called every 10 000 steps with the steps so far.
pub fn soak(
    config: &EnvConfig,
    policy: &mut dyn Policy,
    noise: f64,
    steps: u64,
    seed: u64,
    progress: &mut dyn FnMut(u64),
) -> Result<SoakReport, EnvError> {
    let mut env = TaskEnv::new(config.clone())?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut report = SoakReport::default();
    let record_error = |report: &mut SoakReport, e: EnvError| {
        report.env_errors += 1;
        report.first_error.get_or_insert_with(|| e.to_string());
    };
    let mut episode = 0u64;
    let mut obs = loop {
        match env.reset(seed.wrapping_add(episode)) {
            Ok((obs, _)) => break obs,
            Err(e) => record_error(&mut report, e),
        }
        episode += 1;
        if episode >= 1000 {
            return Ok(report);
        }
    };
    policy.reset(seed.wrapping_add(episode));
    let warmup = steps / 10;
    for t in 0..steps {
        let planned = policy.act(&obs);
        let action = Action(std::array::from_fn(|i| {
            (planned.0[i] + noise * rng.random_range(-1.0..=1.0)).clamp(-1.0, 1.0)
        }));
        let ended = match env.step(&action) {
            Ok(step) => {
                obs = step.obs;
                if !step.obs.to_array().iter().all(|v| v.is_finite()) {
                    report.non_finite_observations += 1;
                }
                if !step.reward.is_finite() {
                    report.non_finite_rewards += 1;
                }
                report.successes += u64::from(step.info.success);
                report.physics_steps += u64::from(step.info.simulated);
                report.physics_faults += u64::from(step.info.physics_fault.is_some());
                step.terminated || step.truncated
            }
            Err(e) => {
                record_error(&mut report, e);
                true
            }
        };
        report.steps += 1;
        if ended {
            report.episodes += 1;
            episode += 1;
            match env.reset(seed.wrapping_add(episode)) {
                Ok((first, _)) => obs = first,
                Err(e) => record_error(&mut report, e),
            }
            policy.reset(seed.wrapping_add(episode));
        }
        if t + 1 == warmup.max(1) {
            report.rss_after_warmup_kib = resident_kib();
        }
        if (t + 1) % 10_000 == 0 {
            progress(t + 1);
        }
    }
    report.rss_end_kib = resident_kib();
    Ok(report)
}
