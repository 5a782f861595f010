//! One differential-IK step: stacks the tasks' and limits' rows into a QP and solves it.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT::NonnegativeConeT,
};

use nalgebra::{Matrix6, Vector6};

use crate::diff_ik::rows::{Limit, LimitRow, Task, TaskRow};
use crate::model::ArmModel;

/// Why one QP step failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QpError {
    /// Damping must be positive for the QP to be strictly convex.
    #[error("damping must be positive and finite, got {0}")]
    BadDamping(f64),
    /// A task or limit produced NaN or infinity.
    #[error("a task or limit row is not finite at q = {0:?}")]
    NonFinite([f64; 6]),
    /// clarabel could not solve the QP.
    #[error("clarabel: {0}")]
    Solver(String),
}

/// Reusable QP state: row buffers and, while the constraint pattern stays the same, the clarabel
/// solver itself (only P, q, A's values and b are updated between solves).
///
/// When the unconstrained minimiser of the QP (one 6×6 Cholesky solve) already satisfies every
/// limit row, it *is* the QP's optimum (KKT with zero multipliers) and clarabel is skipped; set
/// `always_use_solver` to send every step to clarabel instead (same answer to solver tolerance).
#[derive(Default)]
pub struct QpWorkspace {
    /// Send every step to clarabel, even when no limit is active.
    pub always_use_solver: bool,
    /// Steps answered by the unconstrained shortcut, and by clarabel (for benchmarks).
    pub counts: (usize, usize),
    task_rows: Vec<TaskRow>,
    limit_rows: Vec<LimitRow>,
    solver: Option<(Vec<usize>, Vec<usize>, DefaultSolver<f64>)>,
}

/// Column-major upper triangle of a dense 6×6, as clarabel wants P.
fn upper_triangle_csc(dense: &[[f64; 6]; 6]) -> CscMatrix<f64> {
    let mut colptr = vec![0];
    let mut rowval = Vec::with_capacity(21);
    let mut nzval = Vec::with_capacity(21);
    for col in 0..6 {
        for (row, values) in dense.iter().enumerate().take(col + 1) {
            rowval.push(row);
            nzval.push(values[col]);
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(6, 6, colptr, rowval, nzval)
}

/// Rows with one non-zero coefficient are bounds on one joint: keeps only the tightest per
/// joint and direction, so stacked position and velocity limits cost 12 rows instead of 24.
fn merge_bounds(rows: &mut Vec<LimitRow>) {
    let mut tightest: [Option<LimitRow>; 12] = [None; 12];
    rows.retain(|row| {
        let mut nonzero = row.g.iter().enumerate().filter(|(_, g)| **g != 0.0);
        let (Some((i, &g)), None) = (nonzero.next(), nonzero.next()) else {
            return true;
        };
        let slot = 2 * i + usize::from(g < 0.0);
        let normalised = LimitRow {
            g: row.g.map(|v| v / g.abs()),
            h: row.h / g.abs(),
        };
        match &tightest[slot] {
            Some(kept) if kept.h <= normalised.h => {}
            _ => tightest[slot] = Some(normalised),
        }
        false
    });
    rows.extend(tightest.into_iter().flatten());
}

impl QpWorkspace {
    /// A workspace that sends every step to clarabel (no unconstrained shortcut).
    pub fn solver_only() -> Self {
        Self {
            always_use_solver: true,
            ..Self::default()
        }
    }
}

/// `argmin ½xᵀPx + cᵀx` if it satisfies every limit row (within 1e-12), else `None`.
fn unconstrained_if_feasible(
    p_upper: &[[f64; 6]; 6],
    c: &[f64; 6],
    limits: &[LimitRow],
) -> Option<[f64; 6]> {
    let p = Matrix6::from_fn(|r, col| p_upper[r.min(col)][r.max(col)]);
    let x = p.cholesky()?.solve(&-Vector6::from_column_slice(c));
    let feasible = limits.iter().all(|row| {
        let gx: f64 = row.g.iter().zip(x.iter()).map(|(g, x)| g * x).sum();
        gx <= row.h + 1e-12
    });
    feasible.then(|| [x[0], x[1], x[2], x[3], x[4], x[5]])
}

/// G as a sparse matrix holding only its structural non-zeros.
fn limits_csc(rows: &[LimitRow]) -> CscMatrix<f64> {
    let mut colptr = vec![0];
    let mut rowval = Vec::new();
    let mut nzval = Vec::new();
    for col in 0..6 {
        for (r, row) in rows.iter().enumerate() {
            if row.g[col] != 0.0 {
                rowval.push(r);
                nzval.push(row.g[col]);
            }
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(rows.len(), 6, colptr, rowval, nzval)
}

fn settings() -> DefaultSettings<f64> {
    DefaultSettings {
        verbose: false,
        presolve_enable: false,
        ..DefaultSettings::default()
    }
}

/// One differential-IK step: stacks `tasks` and `limits` at `q` into a QP with damping
/// `damping` (per rad²) and returns the optimal `Δq` \[rad\].
pub fn solve_step(
    model: &ArmModel,
    q: &[f64; 6],
    tasks: &[&dyn Task],
    limits: &[&dyn Limit],
    damping: f64,
    ws: &mut QpWorkspace,
) -> Result<[f64; 6], QpError> {
    if !(damping > 0.0 && damping.is_finite()) {
        return Err(QpError::BadDamping(damping));
    }
    ws.task_rows.clear();
    ws.limit_rows.clear();
    for task in tasks {
        task.rows(model, q, &mut ws.task_rows);
    }
    for limit in limits {
        limit.rows(model, q, &mut ws.limit_rows);
    }
    merge_bounds(&mut ws.limit_rows);
    let finite = ws.task_rows.iter().all(|r| {
        r.error.is_finite() && r.weight.is_finite() && r.jacobian.iter().all(|v| v.is_finite())
    }) && ws
        .limit_rows
        .iter()
        .all(|r| r.h.is_finite() && r.g.iter().all(|v| v.is_finite()));
    if !finite {
        return Err(QpError::NonFinite(*q));
    }

    // P = Σ w jᵀj + λI,  c = −Σ w e j.
    let mut p = [[0.0; 6]; 6];
    let mut c = [0.0; 6];
    for row in &ws.task_rows {
        let j = &row.jacobian;
        for (a, p_row) in p.iter_mut().enumerate() {
            c[a] -= row.weight * row.error * j[a];
            for (b, p_ab) in p_row.iter_mut().enumerate().skip(a) {
                *p_ab += row.weight * j[a] * j[b];
            }
        }
    }
    for (a, p_row) in p.iter_mut().enumerate() {
        p_row[a] += damping;
    }
    if !ws.always_use_solver
        && let Some(dq) = unconstrained_if_feasible(&p, &c, &ws.limit_rows)
    {
        ws.counts.0 += 1;
        return Ok(dq);
    }
    ws.counts.1 += 1;
    let p_csc = upper_triangle_csc(&p);
    let g_csc = limits_csc(&ws.limit_rows);
    let h: Vec<f64> = ws.limit_rows.iter().map(|r| r.h).collect();

    let same_pattern = matches!(&ws.solver, Some((colptr, rowval, _))
        if *colptr == g_csc.colptr && *rowval == g_csc.rowval);
    if same_pattern {
        let (_, _, solver) = ws.solver.as_mut().expect("checked above");
        let updated = solver
            .update_P(&p_csc.nzval)
            .and_then(|_| solver.update_q(&c.to_vec()))
            .and_then(|_| solver.update_A(&g_csc.nzval))
            .and_then(|_| solver.update_b(&h));
        updated.map_err(|e| QpError::Solver(e.to_string()))?;
    } else {
        let cones = [NonnegativeConeT(h.len())];
        let solver = DefaultSolver::new(&p_csc, &c, &g_csc, &h, &cones, settings())
            .map_err(|e| QpError::Solver(e.to_string()))?;
        ws.solver = Some((g_csc.colptr.clone(), g_csc.rowval.clone(), solver));
    }
    let (_, _, solver) = ws.solver.as_mut().expect("set above");
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => {
            let x = &solver.solution.x;
            Ok([x[0], x[1], x[2], x[3], x[4], x[5]])
        }
        status => {
            ws.solver = None;
            Err(QpError::Solver(format!("{status:?}")))
        }
    }
}
