//! `bench ik`: the chain IK ([`fairgrasp_kinematics::chain_ik`]) on random reachable poses of
//! several arms, timed beside the FR3's closed form on the same FR3 poses in the same run.
//!
//! A pose is the tip's FK at a configuration drawn uniformly within the joint limits; each solve
//! starts from another such configuration (restarts seeded per pose). Times are wall time per
//! solve on this thread.

use std::time::Instant;

use fairgrasp_kinematics::chain_ik::{ChainIk, ChainIkOptions};
use fairgrasp_kinematics::fairino::fr3;
use fairgrasp_kinematics::{AnalyticIkOptions, EndFrame};
use serde::Serialize;

/// One arm's figures.
#[derive(Clone, Debug, Serialize)]
pub struct IkBenchRow {
    /// What was solved: an arm's chain IK, or the FR3's closed form.
    pub solver: String,
    /// Movable joints.
    pub dof: usize,
    pub poses: usize,
    pub solved: usize,
    /// Median and 90th percentile of one solve \[µs\].
    pub median_us: f64,
    pub p90_us: f64,
    /// Mean attempts of the solved poses (1 = from the given start).
    pub mean_attempts: f64,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn row(
    solver: String,
    dof: usize,
    mut times: Vec<f64>,
    solved: usize,
    attempts: usize,
) -> IkBenchRow {
    times.sort_by(f64::total_cmp);
    IkBenchRow {
        solver,
        dof,
        poses: times.len(),
        solved,
        median_us: percentile(&times, 0.5),
        p90_us: percentile(&times, 0.9),
        mean_attempts: attempts as f64 / solved.max(1) as f64,
    }
}

/// Solves `poses` random reachable poses of `ik` (named `name`), seeded by `seed`.
pub fn bench_chain(name: &str, ik: &ChainIk, poses: usize, seed: u64) -> IkBenchRow {
    let (mut times, mut solved, mut attempts) = (Vec::with_capacity(poses), 0, 0);
    for k in 0..poses as u64 {
        let target = ik.chain.fk(&ik.random_joints(seed ^ (2 * k + 1) << 20));
        let start = ik.random_joints(seed ^ (2 * k) << 20);
        let options = ChainIkOptions {
            seed: k,
            ..ChainIkOptions::default()
        };
        let t = Instant::now();
        let answer = ik.solve(&target, &start, &options);
        times.push(t.elapsed().as_secs_f64() * 1e6);
        if let Ok(s) = answer {
            solved += 1;
            attempts += s.attempts;
        }
    }
    row(
        format!("chain IK: {name}"),
        ik.dof(),
        times,
        solved,
        attempts,
    )
}

/// The FR3's closed form on the poses [`bench_chain`] gives `fr3_chain` (its chain to `tool0`):
/// all branches, solved when one is within the limits.
pub fn bench_fr3_closed_form(fr3_chain: &ChainIk, poses: usize, seed: u64) -> IkBenchRow {
    let model = fr3();
    let options = AnalyticIkOptions::default();
    let (mut times, mut solved) = (Vec::with_capacity(poses), 0);
    for k in 0..poses as u64 {
        let target = fr3_chain
            .chain
            .fk(&fr3_chain.random_joints(seed ^ (2 * k + 1) << 20));
        let t = Instant::now();
        let answer = model.ik_analytic(&target, EndFrame::Flange, &options);
        times.push(t.elapsed().as_secs_f64() * 1e6);
        if answer.is_ok_and(|branches| branches.iter().any(|b| b.in_limits)) {
            solved += 1;
        }
    }
    row("closed form: FR3".into(), 6, times, solved, solved)
}
