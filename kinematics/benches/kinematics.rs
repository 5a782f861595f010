//! Criterion benchmarks: FK, Jacobian, closed-form IK (all branches), QP steps and QP IK solves.
//!
//! Run: `cargo bench -p fairgrasp-kinematics --bench kinematics`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use fairgrasp_kinematics::diff_ik::{
    FrameTask, JointPositionLimit, QpWorkspace, VelocityLimit, solve_step,
};
use fairgrasp_kinematics::{AnalyticIkOptions, ArmKind, ArmModel, EndFrame, Pose, QpIkOptions};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// 256 seeded in-limit configurations.
fn configurations(model: &ArmModel, seed: u64) -> Vec<[f64; 6]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..256)
        .map(|_| model.joints.map(|j| rng.random_range(j.lower..=j.upper)))
        .collect()
}

fn fk(c: &mut Criterion) {
    let model = ArmKind::Fr3.model();
    let qs = configurations(&model, 1);
    let mut i = 0;
    c.bench_function("fk/tcp", |b| {
        b.iter(|| {
            i = (i + 1) % qs.len();
            black_box(model.fk_tcp(black_box(&qs[i])))
        })
    });
    c.bench_function("fk/tcp_jacobian", |b| {
        b.iter(|| {
            i = (i + 1) % qs.len();
            black_box(model.jacobian(black_box(&qs[i]), EndFrame::Tcp))
        })
    });
}

fn analytic_ik(c: &mut Criterion) {
    let model = ArmKind::Fr3.model();
    let targets: Vec<Pose> = configurations(&model, 2)
        .iter()
        .map(|q| model.fk_flange(q))
        .collect();
    let options = AnalyticIkOptions::default();
    let mut i = 0;
    c.bench_function("ik/analytic_all_branches", |b| {
        b.iter(|| {
            i = (i + 1) % targets.len();
            black_box(model.ik_analytic(black_box(&targets[i]), EndFrame::Flange, &options))
        })
    });
}

fn qp_ik(c: &mut Criterion) {
    let model = ArmKind::Fr3.model();
    let starts = configurations(&model, 3);
    // Tracking: the target is the pose of the start perturbed by up to ±0.1 rad per joint
    // (a few centimetres), as when following a grasp approach.
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let tracking: Vec<([f64; 6], Pose)> = starts
        .iter()
        .map(|q| {
            let mut goal = *q;
            for (g, spec) in goal.iter_mut().zip(&model.joints) {
                *g = (*g + rng.random_range(-0.1..0.1)).clamp(spec.lower, spec.upper);
            }
            (*q, model.fk_tcp(&goal))
        })
        .collect();
    let far_goals = configurations(&model, 5);
    let options = QpIkOptions {
        frame: EndFrame::Tcp,
        ..QpIkOptions::default()
    };
    let mut ws = QpWorkspace::default();
    let mut i = 0;
    c.bench_function("ik/qp_solve_tracking", |b| {
        b.iter(|| {
            i = (i + 1) % tracking.len();
            let (start, target) = &tracking[i];
            black_box(model.ik_qp_with(target, start, &options, &mut ws))
        })
    });
    let mut solver_only = QpWorkspace::solver_only();
    c.bench_function("ik/qp_solve_tracking_clarabel_every_step", |b| {
        b.iter(|| {
            i = (i + 1) % tracking.len();
            let (start, target) = &tracking[i];
            black_box(model.ik_qp_with(target, start, &options, &mut solver_only))
        })
    });
    let mut group = c.benchmark_group("ik");
    group.sample_size(20);
    group.bench_function("qp_solve_random_start_random_target", |b| {
        b.iter(|| {
            i = (i + 1) % far_goals.len();
            let target = model.fk_tcp(&far_goals[i]);
            let options = QpIkOptions {
                seed: i as u64,
                ..options
            };
            black_box(model.ik_qp_with(&target, &starts[i], &options, &mut ws))
        })
    });
    group.finish();

    let task = FrameTask::new(EndFrame::Tcp, tracking[0].1, 1.0, 0.25);
    let limits = (
        JointPositionLimit::default(),
        VelocityLimit {
            dt: 0.1,
            scale: 1.0,
        },
    );
    let mut clarabel_ws = QpWorkspace::solver_only();
    c.bench_function("ik/qp_step_clarabel", |b| {
        b.iter(|| {
            black_box(solve_step(
                &model,
                &starts[0],
                &[&task],
                &[&limits.0, &limits.1],
                1e-6,
                &mut clarabel_ws,
            ))
        })
    });
}

criterion_group!(benches, fk, analytic_ik, qp_ik);
criterion_main!(benches);
