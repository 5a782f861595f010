//! [`ChainIk`]: the solver, its options, answers and errors.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::chain_ik::step::bounded_step;

use crate::pose::Pose;
use crate::restart::{
    IterativeIkSolution, RestartSettings, Restarted, RestartedIk, SplitMix64,
    finite_target_and_start, solve_with_restarts,
};
use crate::urdf::{SerialChain, UrdfError, UrdfRobot};

/// Settings of [`ChainIk::solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChainIkOptions {
    /// Converged when the position error is at most this \[m\] …
    pub position_tolerance: f64,
    /// … and the orientation error at most this \[rad\].
    pub orientation_tolerance: f64,
    /// Iterations per attempt.
    pub max_iterations: usize,
    /// Attempts: the first from the given start, the rest from random in-limit configurations.
    pub max_attempts: usize,
    /// Largest step of any joint per iteration \[rad or m\].
    pub max_step: f64,
    /// Constant damping λ₀.
    pub damping: f64,
    /// Error-dependent damping κ: λ = λ₀ + κ·‖e‖².
    pub error_damping: f64,
    /// Weight of orientation error relative to position error \[m²/rad²\].
    pub orientation_weight: f64,
    /// Longest position error trusted in one step \[m\].
    pub position_clamp: f64,
    /// Longest orientation error trusted in one step \[rad\].
    pub orientation_clamp: f64,
    /// Seed of the restarts' random configurations (the same seed, the same answer).
    pub seed: u64,
}

impl Default for ChainIkOptions {
    fn default() -> Self {
        Self {
            position_tolerance: 1e-4,
            orientation_tolerance: 1e-3,
            max_iterations: 40,
            max_attempts: 100,
            max_step: 0.5,
            damping: 1e-9,
            error_damping: 1e-3,
            orientation_weight: 0.25,
            position_clamp: 0.2,
            orientation_clamp: 0.5,
            seed: 0,
        }
    }
}

/// A converged solve.
pub type ChainIkSolution = IterativeIkSolution<Vec<f64>>;

/// Why the chain IK gave no answer.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChainIkError {
    #[error("the start has {got} joint values; the chain to `{tip}` has {expected} movable joints")]
    StartLength {
        tip: String,
        expected: usize,
        got: usize,
    },
    #[error("start joint `{joint}` = {value:.4} is outside its limits [{lower:.4}, {upper:.4}]")]
    StartOutOfLimits {
        joint: String,
        value: f64,
        lower: f64,
        upper: f64,
    },
    #[error("the target pose or the start joints are not finite")]
    NonFinite,
    #[error(
        "did not converge: best residual {position_error_m:.3e} m / {orientation_error_rad:.3e} rad after {iterations} QP steps in {attempts} attempts"
    )]
    NotConverged {
        best_joints: Vec<f64>,
        position_error_m: f64,
        orientation_error_rad: f64,
        iterations: usize,
        attempts: usize,
    },
    #[error("clarabel: {0}")]
    Solver(String),
}

/// IK for one serial chain of a URDF: its joints, their limits, and the solver.
#[derive(Clone, Debug)]
pub struct ChainIk {
    pub chain: SerialChain,
    /// Names of the movable joints, in chain order.
    pub names: Vec<String>,
    /// Lower and upper limits of each movable joint \[rad or m\] (continuous joints: ±2π).
    pub lower: Vec<f64>,
    pub upper: Vec<f64>,
}

impl ChainIk {
    /// The chain of `robot` from its root to `tip` (its only leaf when `None`).
    pub fn new(robot: &UrdfRobot, tip: Option<&str>) -> Result<Self, UrdfError> {
        let chain = robot.chain(tip)?;
        let movable: Vec<_> = chain
            .joints
            .iter()
            .filter(|j| j.kind.is_single_axis())
            .collect();
        let limit = |j: &crate::urdf::UrdfJoint| {
            j.limits
                .unwrap_or([-std::f64::consts::TAU, std::f64::consts::TAU])
        };
        Ok(Self {
            names: movable.iter().map(|j| j.name.clone()).collect(),
            lower: movable.iter().map(|j| limit(j)[0]).collect(),
            upper: movable.iter().map(|j| limit(j)[1]).collect(),
            chain,
        })
    }

    /// Number of movable joints.
    pub fn dof(&self) -> usize {
        self.names.len()
    }

    /// A configuration drawn uniformly within the limits from `seed`.
    pub fn random_joints(&self, seed: u64) -> Vec<f64> {
        let mut rng = SplitMix64(seed);
        self.draw(&mut rng)
    }

    fn draw(&self, rng: &mut SplitMix64) -> Vec<f64> {
        (0..self.dof())
            .map(|i| self.lower[i] + (self.upper[i] - self.lower[i]) * rng.next_unit())
            .collect()
    }

    /// At `q`: the Gauss–Newton normal equations of the weighted, clamped tip error — `JᵀWJ`
    /// and `JᵀWe` — and the unclamped position \[m\] and orientation \[rad\] errors.
    fn normal_equations(
        &self,
        target: &Pose,
        q: &[f64],
        o: &ChainIkOptions,
    ) -> (DMatrix<f64>, DVector<f64>, f64, f64) {
        let (now, mut jacobian) = self.chain.fk_jacobian(q);
        let dp: Vector3<f64> = target.iso.translation.vector - now.iso.translation.vector;
        let dr: Vector3<f64> = (target.iso.rotation * now.iso.rotation.inverse()).scaled_axis();
        let (np, nr) = (dp.norm(), dr.norm());
        let dp = dp * (o.position_clamp / np.max(o.position_clamp));
        let dr = dr * (o.orientation_clamp / nr.max(o.orientation_clamp));
        // √W on the rows: orientation rows scaled by √w.
        let sw = o.orientation_weight.sqrt();
        jacobian.rows_mut(3, 3).scale_mut(sw);
        let e = DVector::from_column_slice(&[dp.x, dp.y, dp.z, sw * dr.x, sw * dr.y, sw * dr.z]);
        let rhs = jacobian.tr_mul(&e);
        (jacobian.tr_mul(&jacobian), rhs, np, nr)
    }

    /// Places the chain's tip at `target` (in the chain's root frame) starting from `start`.
    pub fn solve(
        &self,
        target: &Pose,
        start: &[f64],
        options: &ChainIkOptions,
    ) -> Result<ChainIkSolution, ChainIkError> {
        self.check_start(target, start)?;
        let settings = RestartSettings::new(
            (options.position_tolerance, options.orientation_tolerance),
            options.max_iterations,
            options.max_attempts,
            options.seed,
        );
        let mut problem = TipProblem {
            ik: self,
            target,
            options,
        };
        match solve_with_restarts(&mut problem, &start.to_vec(), &settings)? {
            Restarted::Converged(solution) => Ok(solution),
            Restarted::NotConverged(r) => Err(ChainIkError::NotConverged {
                best_joints: r.joints,
                position_error_m: r.position_error_m,
                orientation_error_rad: r.orientation_error_rad,
                iterations: r.iterations,
                attempts: r.attempts,
            }),
        }
    }

    /// Refuses a start of the wrong length, non-finite values, or a start outside the limits.
    fn check_start(&self, target: &Pose, start: &[f64]) -> Result<(), ChainIkError> {
        let n = self.dof();
        if start.len() != n {
            return Err(ChainIkError::StartLength {
                tip: self.chain.tip.clone(),
                expected: n,
                got: start.len(),
            });
        }
        if !finite_target_and_start(target, start) {
            return Err(ChainIkError::NonFinite);
        }
        match (0..n).find(|&i| start[i] < self.lower[i] || start[i] > self.upper[i]) {
            Some(i) => Err(ChainIkError::StartOutOfLimits {
                joint: self.names[i].clone(),
                value: start[i],
                lower: self.lower[i],
                upper: self.upper[i],
            }),
            None => Ok(()),
        }
    }
}

/// The chain's tip task as a [`RestartedIk`] problem: the Gauss–Newton normal equations at a
/// configuration, and one bounded step ([`bounded_step`]) within the limits and `max_step`.
struct TipProblem<'a> {
    ik: &'a ChainIk,
    target: &'a Pose,
    options: &'a ChainIkOptions,
}

impl RestartedIk for TipProblem<'_> {
    type Joints = Vec<f64>;
    /// `JᵀWJ` and `JᵀWe` at the configuration.
    type Linearisation = (DMatrix<f64>, DVector<f64>);
    type Error = ChainIkError;

    fn evaluate(&mut self, q: &Vec<f64>) -> (f64, f64, Self::Linearisation) {
        let (hessian, rhs, dp, dr) = self.ik.normal_equations(self.target, q, self.options);
        (dp, dr, (hessian, rhs))
    }

    fn step(
        &mut self,
        q: &mut Vec<f64>,
        (dp, dr): (f64, f64),
        (hessian, rhs): Self::Linearisation,
    ) -> Result<(), ChainIkError> {
        let (ik, o) = (self.ik, self.options);
        let damping = o.damping + o.error_damping * (dp * dp + o.orientation_weight * dr * dr);
        let bounds: Vec<(f64, f64)> = (0..ik.dof())
            .map(|i| {
                let lo = (ik.lower[i] - q[i]).max(-o.max_step);
                let hi = (ik.upper[i] - q[i]).min(o.max_step);
                (lo, hi)
            })
            .collect();
        let dq = bounded_step(hessian, &rhs, damping, &bounds).map_err(ChainIkError::Solver)?;
        for (i, value) in q.iter_mut().enumerate() {
            // The interior-point answer may sit 1e-12 outside a bound.
            *value = (*value + dq[i]).clamp(ik.lower[i], ik.upper[i]);
        }
        Ok(())
    }

    fn draw(&self, rng: &mut SplitMix64) -> Vec<f64> {
        self.ik.draw(rng)
    }
}
