//! QP differential IK: degenerate cases pinned by name, convergence, and joint limits.

mod common;

use rand::Rng;

use fairgrasp_kinematics::diff_ik::{
    FrameTask, JointPositionLimit, PostureTask, QpWorkspace, VelocityLimit, solve_step,
};
use fairgrasp_kinematics::{ArmKind, EndFrame, Pose, QpIkError, QpIkOptions};

const Q_MID: [f64; 6] = [0.3, -1.2, 1.1, -1.4, 0.8, 0.5];

fn norm(v: &[f64; 6]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Both ways of answering a step: the unconstrained shortcut where it applies, and clarabel.
fn workspaces() -> [QpWorkspace; 2] {
    [QpWorkspace::default(), QpWorkspace::solver_only()]
}

#[test]
fn no_task_gives_zero_step() {
    let model = ArmKind::Fr3.model();
    let limit = JointPositionLimit::default();
    for mut ws in workspaces() {
        let dq = solve_step(&model, &Q_MID, &[], &[&limit], 1e-3, &mut ws).unwrap();
        // clarabel's interior point stops at a 1e-8 duality gap: zero to about 1e-6 rad.
        assert!(norm(&dq) < 1e-5, "{dq:?}");
    }
}

#[test]
fn a_fulfilled_task_gives_zero_step() {
    let model = ArmKind::Fr3.model();
    let task = FrameTask::new(EndFrame::Tcp, model.fk_tcp(&Q_MID), 1.0, 1.0);
    let limit = VelocityLimit {
        dt: 0.1,
        scale: 1.0,
    };
    for mut ws in workspaces() {
        let dq = solve_step(&model, &Q_MID, &[&task], &[&limit], 1e-6, &mut ws).unwrap();
        assert!(norm(&dq) < 1e-5, "{dq:?}");
    }
}

#[test]
fn the_unconstrained_shortcut_and_clarabel_give_the_same_step() {
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(22);
    let [mut fast, mut solver] = workspaces();
    let position = JointPositionLimit { margin: 0.01 };
    let velocity = VelocityLimit {
        dt: 0.05,
        scale: 1.0,
    };
    for _ in 0..300 {
        let q = common::random_in_limits(&model, &mut rng);
        let mut goal = q;
        for g in goal.iter_mut() {
            *g += rng.random_range(-0.3..0.3);
        }
        let task = FrameTask::new(EndFrame::Tcp, model.fk_tcp(&goal), 1.0, 0.5);
        let a = solve_step(
            &model,
            &q,
            &[&task],
            &[&position, &velocity],
            1e-4,
            &mut fast,
        )
        .unwrap();
        let b = solve_step(
            &model,
            &q,
            &[&task],
            &[&position, &velocity],
            1e-4,
            &mut solver,
        )
        .unwrap();
        assert!(common::max_abs_diff(&a, &b) < 1e-5, "{a:?} vs {b:?}");
    }
    assert!(
        fast.counts.0 > 0 && fast.counts.1 > 0,
        "both paths exercised: {:?}",
        fast.counts
    );
    assert_eq!(solver.counts.0, 0);
}

#[test]
fn a_posture_task_alone_steps_straight_to_its_target() {
    let model = ArmKind::Fr3.model();
    let mut ws = QpWorkspace::default();
    let target = [0.0, -1.0, 1.0, -1.0, 1.0, 0.0];
    let task = PostureTask { target, cost: 1.0 };
    let dq = solve_step(&model, &Q_MID, &[&task], &[], 1e-9, &mut ws).unwrap();
    for i in 0..6 {
        assert!((Q_MID[i] + dq[i] - target[i]).abs() < 1e-6);
    }
}

#[test]
fn the_velocity_limit_bounds_every_joint_step() {
    let model = ArmKind::Fr3.model();
    let mut ws = QpWorkspace::default();
    let task = PostureTask {
        target: [2.0, -3.0, -2.0, 0.5, -2.0, 2.0],
        cost: 1.0,
    };
    let limit = VelocityLimit {
        dt: 0.01,
        scale: 1.0,
    };
    let dq = solve_step(&model, &Q_MID, &[&task], &[&limit], 1e-9, &mut ws).unwrap();
    for (i, (d, spec)) in dq.iter().zip(&model.joints).enumerate() {
        let bound = spec.max_velocity * 0.01;
        assert!(d.abs() <= bound + 1e-9, "joint {i}: {} > {bound}", *d);
        assert!(d.abs() >= 0.99 * bound, "joint {i} should saturate: {}", *d);
    }
}

#[test]
fn a_step_never_crosses_the_joint_limits_even_when_the_task_pulls_beyond_them() {
    let model = ArmKind::Fr3.model();
    let mut ws = QpWorkspace::default();
    let upper = model.upper_limits();
    let q = [
        upper[0] - 0.01,
        -1.2,
        upper[2] - 0.02,
        -1.4,
        0.8,
        upper[5] - 0.001,
    ];
    let beyond = [
        upper[0] + 1.0,
        -1.2,
        upper[2] + 1.0,
        -1.4,
        0.8,
        upper[5] + 1.0,
    ];
    let task = PostureTask {
        target: beyond,
        cost: 1.0,
    };
    let limit = JointPositionLimit { margin: 0.0 };
    let dq = solve_step(&model, &q, &[&task], &[&limit], 1e-9, &mut ws).unwrap();
    for i in 0..6 {
        assert!(q[i] + dq[i] <= upper[i] + 1e-9, "joint {i}");
    }
    assert!(
        (q[0] + dq[0] - upper[0]).abs() < 1e-6,
        "j1 should stop at its limit"
    );
}

#[test]
fn non_positive_damping_is_refused() {
    let model = ArmKind::Fr3.model();
    let mut ws = QpWorkspace::default();
    assert!(solve_step(&model, &Q_MID, &[], &[], 0.0, &mut ws).is_err());
    assert!(solve_step(&model, &Q_MID, &[], &[], f64::NAN, &mut ws).is_err());
}

#[test]
fn qp_ik_converges_on_999_of_1000_random_reachable_targets_from_random_starts() {
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(21);
    let options = QpIkOptions {
        frame: EndFrame::Tcp,
        ..QpIkOptions::default()
    };
    let (mut converged, mut iterations, mut restarts) = (0, 0, 0);
    let mut failures = Vec::new();
    for n in 0..1000 {
        let goal = common::random_in_limits(&model, &mut rng);
        let start = common::random_in_limits(&model, &mut rng);
        let target = model.fk_tcp(&goal);
        let options = QpIkOptions { seed: n, ..options };
        match model.ik_qp(&target, &start, &options) {
            Ok(solution) => {
                converged += 1;
                iterations += solution.iterations;
                restarts += solution.attempts - 1;
                assert!(
                    model.in_limits(&solution.joints, 0.0),
                    "{:?}",
                    solution.joints
                );
                let (dp, dr) = model.fk_tcp(&solution.joints).distance_to(&target);
                assert!(dp <= 1e-4 && dr <= 1e-3, "{dp:e} m {dr:e} rad");
            }
            Err(QpIkError::NotConverged { best_joints, .. }) => {
                assert!(model.in_limits(&best_joints, 0.0));
                failures.push(n);
            }
            Err(e) => panic!("target {n}: {e}"),
        }
    }
    eprintln!(
        "QP IK: {converged}/1000 converged, {:.1} QP steps and {:.2} restarts on average; failed: {failures:?}",
        iterations as f64 / converged as f64,
        restarts as f64 / converged as f64
    );
    assert!(converged >= 999, "{converged}/1000; failures {failures:?}");
}

#[test]
fn qp_ik_with_the_same_seed_gives_the_same_answer() {
    let model = ArmKind::Fr3.model();
    let target = model.fk_flange(&[-2.0, -3.5, -2.0, 0.5, -2.5, 2.5]);
    let start = [0.0, -1.0, 1.0, -1.0, 1.0, 0.0];
    let options = QpIkOptions {
        seed: 5,
        ..QpIkOptions::default()
    };
    let a = model.ik_qp(&target, &start, &options).unwrap();
    let b = model.ik_qp(&target, &start, &options).unwrap();
    assert_eq!(a, b);
}

#[test]
fn an_unreachable_target_reports_failure_with_the_residual() {
    let model = ArmKind::Fr3.model();
    let target = Pose::from_xyz([1.5, 0.0, 0.3]);
    let options = QpIkOptions {
        max_attempts: 3,
        ..QpIkOptions::default()
    };
    match model.ik_qp(&target, &Q_MID, &options) {
        Err(QpIkError::NotConverged {
            position_error_m,
            best_joints,
            ..
        }) => {
            assert!(position_error_m > 0.5, "{position_error_m}");
            assert!(model.in_limits(&best_joints, 0.0));
        }
        other => panic!("expected NotConverged, got {other:?}"),
    }
}

#[test]
fn a_start_outside_the_limits_is_refused_naming_the_joint() {
    let model = ArmKind::Fr3.model();
    let start = [0.0, 2.0, 0.0, 0.0, 0.0, 0.0]; // j2 upper limit is 85 deg
    let err = model
        .ik_qp(&model.fk_flange(&Q_MID), &start, &QpIkOptions::default())
        .unwrap_err();
    assert!(err.to_string().contains("j2"), "{err}");
}
