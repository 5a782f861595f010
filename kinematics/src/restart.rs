//! The restart loop both iterative IK solvers run ([`crate::qp_ik`] for the FR3,
//! [`crate::chain_ik`] for any URDF chain), and the seeded generator it draws restart
//! configurations from: the same seed, the same restarts, on any platform.
//!
//! An attempt takes steps from its start until the residual is within tolerance (converged), it
//! stalls (less than 10 % progress over 8 steps) or it runs out of iterations; the first attempt
//! starts from the caller's configuration, the others from random in-limit configurations, as
//! TRAC-IK restarts its solvers. The solver supplies the residual and the step
//! ([`RestartedIk`]); the loop keeps the best configuration seen for the error it reports.

use serde::Serialize;

use crate::pose::Pose;

/// SplitMix64: a tiny, seeded, portable generator.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    /// A number in [0, 1).
    pub(crate) fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A stall: less than 10 % progress (this factor of the score) over [`STALL_STEPS`] steps.
const STALL_PROGRESS: f64 = 0.9;
/// Steps without [`STALL_PROGRESS`] after which an attempt gives up.
const STALL_STEPS: usize = 8;

/// The loop's settings, shared by both solvers' options.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RestartSettings {
    /// Converged when the position error is at most this \[m\] …
    pub position_tolerance: f64,
    /// … and the orientation error at most this \[rad\].
    pub orientation_tolerance: f64,
    /// Steps per attempt.
    pub max_iterations: usize,
    /// Attempts: the first from the start, the rest from random configurations.
    pub max_attempts: usize,
    /// Seed of the restarts' random configurations.
    pub seed: u64,
}

impl RestartSettings {
    /// Settings from a solver's options: the tolerances \[m, rad\], iterations per attempt,
    /// attempts and seed.
    pub fn new(
        (position_tolerance, orientation_tolerance): (f64, f64),
        max_iterations: usize,
        max_attempts: usize,
        seed: u64,
    ) -> Self {
        Self {
            position_tolerance,
            orientation_tolerance,
            max_iterations,
            max_attempts,
            seed,
        }
    }
}

/// What a solver gives the restart loop: its residual, its step and its random configurations.
pub(crate) trait RestartedIk {
    /// A configuration: joint values \[rad or m\].
    type Joints: Clone;
    /// What the step needs from the evaluation at a configuration (the solver's linearisation).
    type Linearisation;
    type Error;

    /// At `q`: the position \[m\] and orientation \[rad\] errors, and the linearisation to step
    /// from.
    fn evaluate(&mut self, q: &Self::Joints) -> (f64, f64, Self::Linearisation);

    /// Moves `q` one step toward the target, within the joint limits.
    fn step(
        &mut self,
        q: &mut Self::Joints,
        errors: (f64, f64),
        linearisation: Self::Linearisation,
    ) -> Result<(), Self::Error>;

    /// A configuration drawn uniformly within the limits.
    fn draw(&self, rng: &mut SplitMix64) -> Self::Joints;
}

/// A converged solve of an iterative IK ([`crate::QpIkSolution`],
/// [`crate::chain_ik::ChainIkSolution`]), or the best configuration of one that did not converge.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct IterativeIkSolution<J> {
    /// The joint values \[rad, or m for a sliding joint\], in chain order, within the limits.
    pub joints: J,
    /// Position error at the end \[m\].
    pub position_error_m: f64,
    /// Orientation error at the end \[rad\].
    pub orientation_error_rad: f64,
    /// QP steps taken over all attempts.
    pub iterations: usize,
    /// Attempts used (1 = converged from the given start).
    pub attempts: usize,
}

/// How the loop ended: converged, or the best configuration seen when out of attempts.
pub(crate) enum Restarted<J> {
    Converged(IterativeIkSolution<J>),
    NotConverged(IterativeIkSolution<J>),
}

/// The best configuration seen so far, by the score `dp/tol_p + dr/tol_r`.
struct Best<J> {
    score: f64,
    joints: J,
    errors: (f64, f64),
}

/// Runs attempts from `start`, then from random configurations, until one converges.
pub(crate) fn solve_with_restarts<P: RestartedIk>(
    problem: &mut P,
    start: &P::Joints,
    settings: &RestartSettings,
) -> Result<Restarted<P::Joints>, P::Error> {
    let mut rng = SplitMix64(settings.seed);
    let mut best = Best {
        score: f64::INFINITY,
        joints: start.clone(),
        errors: (0.0, 0.0),
    };
    let mut iterations = 0;
    let mut q = start.clone();
    for attempt in 1..=settings.max_attempts {
        if attempt > 1 {
            q = problem.draw(&mut rng);
        }
        if let Some(errors) = attempt_from(problem, &mut q, settings, &mut best, &mut iterations)? {
            return Ok(Restarted::Converged(IterativeIkSolution {
                joints: q,
                position_error_m: errors.0,
                orientation_error_rad: errors.1,
                iterations,
                attempts: attempt,
            }));
        }
    }
    Ok(Restarted::NotConverged(IterativeIkSolution {
        joints: best.joints,
        position_error_m: best.errors.0,
        orientation_error_rad: best.errors.1,
        iterations,
        attempts: settings.max_attempts,
    }))
}

/// One attempt from `q`: steps until converged (the errors), stalled or out of iterations
/// (`None`); `best` and `iterations` carry over between attempts.
fn attempt_from<P: RestartedIk>(
    problem: &mut P,
    q: &mut P::Joints,
    settings: &RestartSettings,
    best: &mut Best<P::Joints>,
    iterations: &mut usize,
) -> Result<Option<(f64, f64)>, P::Error> {
    let mut stalled_since = (f64::INFINITY, 0);
    for it in 0..=settings.max_iterations {
        let (dp, dr, linearisation) = problem.evaluate(q);
        let score = dp / settings.position_tolerance + dr / settings.orientation_tolerance;
        if score < best.score {
            *best = Best {
                score,
                joints: q.clone(),
                errors: (dp, dr),
            };
        }
        if dp <= settings.position_tolerance && dr <= settings.orientation_tolerance {
            return Ok(Some((dp, dr)));
        }
        if score < STALL_PROGRESS * stalled_since.0 {
            stalled_since = (score, it);
        } else if it - stalled_since.1 >= STALL_STEPS || it == settings.max_iterations {
            return Ok(None);
        }
        problem.step(q, (dp, dr), linearisation)?;
        *iterations += 1;
    }
    Ok(None)
}

/// Whether the target pose and the start joints are all finite (both solvers refuse otherwise).
pub(crate) fn finite_target_and_start(target: &Pose, start: &[f64]) -> bool {
    target
        .xyz()
        .iter()
        .chain(&target.quat_xyzw())
        .chain(start)
        .all(|v| v.is_finite())
}
