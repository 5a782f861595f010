//! One bounded QP step of [`super::ChainIk`]: `min ½·dqᵀ(H + λI)dq − gᵀdq` with `lo ≤ dq ≤ hi`.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT::NonnegativeConeT,
};
use nalgebra::{DMatrix, DVector};

/// The step: the box QP solved by a primal active set (exact for a box and a positive definite
/// `H`; N×N Cholesky solves, a handful at most), else, if that does not settle within 3N
/// rounds, by clarabel.
pub(super) fn bounded_step(
    mut hessian: DMatrix<f64>,
    gradient: &DVector<f64>,
    damping: f64,
    bounds: &[(f64, f64)],
) -> Result<DVector<f64>, String> {
    let n = gradient.len();
    for i in 0..n {
        hessian[(i, i)] += damping;
    }
    match active_set(&hessian, gradient, bounds) {
        Some(dq) => Ok(dq),
        None => clarabel_step(&hessian, gradient, bounds),
    }
}

/// The box QP by clarabel.
fn clarabel_step(
    hessian: &DMatrix<f64>,
    gradient: &DVector<f64>,
    bounds: &[(f64, f64)],
) -> Result<DVector<f64>, String> {
    let n = gradient.len();
    // P: the upper triangle, column by column; A = [I; −I], b = [hi; −lo], A·dq + s = b, s ≥ 0.
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for col in 0..n {
        for row in 0..=col {
            rowval.push(row);
            nzval.push(hessian[(row, col)]);
        }
        colptr.push(rowval.len());
    }
    let p = CscMatrix::new(n, n, colptr, rowval, nzval);
    let a = CscMatrix::new(
        2 * n,
        n,
        (0..=n).map(|c| 2 * c).collect(),
        (0..n).flat_map(|c| [c, n + c]).collect(),
        (0..n).flat_map(|_| [1.0, -1.0]).collect(),
    );
    let b: Vec<f64> = bounds
        .iter()
        .map(|b| b.1)
        .chain(bounds.iter().map(|b| -b.0))
        .collect();
    let q: Vec<f64> = gradient.iter().map(|g| -g).collect();
    let settings = DefaultSettings {
        verbose: false,
        ..DefaultSettings::default()
    };
    let cones = [NonnegativeConeT(2 * n)];
    let mut solver =
        DefaultSolver::new(&p, &q, &a, &b, &cones, settings).map_err(|e| format!("{e:?}"))?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            Ok(DVector::from_column_slice(&solver.solution.x))
        }
        status => Err(format!("{status:?}")),
    }
}

/// Primal active set for `min ½·xᵀHx − gᵀx`, `lo ≤ x ≤ hi`: solve for the free variables with the
/// others at their bounds; pin the free variable that crosses a bound first along the way from
/// the current point; release a pinned one whose multiplier says it wants inside. `None` if it
/// does not settle within 3N rounds or `H` is not positive definite.
fn active_set(h: &DMatrix<f64>, g: &DVector<f64>, bounds: &[(f64, f64)]) -> Option<DVector<f64>> {
    let n = g.len();
    // Which variables sit at a bound: 0 free, -1 at lo, +1 at hi.
    let mut at = vec![0i8; n];
    let mut x = DVector::from_iterator(n, bounds.iter().map(|b| 0f64.clamp(b.0, b.1)));
    for _ in 0..3 * n + 1 {
        let free: Vec<usize> = (0..n).filter(|&i| at[i] == 0).collect();
        // The free variables' optimum with the pinned ones held: H_ff·x_f = g_f − H_fp·x_p.
        let mut target = x.clone();
        if !free.is_empty() {
            let hff = DMatrix::from_fn(free.len(), free.len(), |r, c| h[(free[r], free[c])]);
            let rhs = DVector::from_iterator(
                free.len(),
                free.iter().map(|&i| {
                    g[i] - (0..n)
                        .filter(|&j| at[j] != 0)
                        .map(|j| h[(i, j)] * x[j])
                        .sum::<f64>()
                }),
            );
            let xf = hff.cholesky()?.solve(&rhs);
            for (k, &i) in free.iter().enumerate() {
                target[i] = xf[k];
            }
        }
        // Walk from x toward the target; stop at the first bound crossed.
        let mut step = 1.0;
        let mut blocking = None;
        for &i in &free {
            let d = target[i] - x[i];
            let room = if d > 0.0 {
                bounds[i].1 - x[i]
            } else {
                bounds[i].0 - x[i]
            };
            if d != 0.0 && room / d < step {
                step = (room / d).max(0.0);
                blocking = Some((i, if d > 0.0 { 1 } else { -1 }));
            }
        }
        for &i in &free {
            x[i] += step * (target[i] - x[i]);
        }
        if let Some((i, side)) = blocking {
            x[i] = if side > 0 { bounds[i].1 } else { bounds[i].0 };
            at[i] = side;
            continue;
        }
        // At the optimum of this face: release a pinned variable whose gradient points inside.
        let gradient = h * &x - g;
        let wants_in = (0..n)
            .filter(|&i| (at[i] > 0 && gradient[i] > 1e-12) || (at[i] < 0 && gradient[i] < -1e-12))
            .max_by(|&a, &b| gradient[a].abs().total_cmp(&gradient[b].abs()));
        match wants_in {
            Some(i) => at[i] = 0,
            None => return Some(x),
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_active_set_finds_clarabels_optimum_of_random_box_qps() {
        let mut state = 7u64;
        let mut unit = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let mut pinned = 0;
        for _ in 0..300 {
            let n = 6 + (unit() + 0.5 > 0.5) as usize;
            let m = DMatrix::from_fn(6, n, |_, _| unit());
            let h = m.transpose() * &m + DMatrix::identity(n, n) * 1e-3;
            let g = DVector::from_fn(n, |_, _| 2.0 * unit());
            let bounds: Vec<(f64, f64)> = (0..n)
                .map(|_| (-0.5 * unit().abs(), 0.5 * unit().abs()))
                .collect();
            let fast = active_set(&h, &g, &bounds).expect("settles");
            let reference = clarabel_step(&h, &g, &bounds).unwrap();
            let cost = |x: &DVector<f64>| 0.5 * x.dot(&(&h * x)) - g.dot(x);
            assert!(
                cost(&fast) <= cost(&reference) + 1e-7,
                "{} vs {}",
                cost(&fast),
                cost(&reference)
            );
            assert!((0..n).all(|i| fast[i] >= bounds[i].0 && fast[i] <= bounds[i].1));
            pinned += (0..n)
                .filter(|&i| fast[i] == bounds[i].0 || fast[i] == bounds[i].1)
                .count();
        }
        assert!(
            pinned > 300,
            "the bounds were active ({pinned} pinned variables)"
        );
    }
}
