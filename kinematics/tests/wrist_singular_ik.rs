//! Closed-form IK where the wrist is singular (joint 5 at or near 0): joints 2, 3, 4 and 6 are
//! parallel there, θ6 is free, and the FK pose of in-limit joints must never be "out of reach".

mod common;

use fairgrasp_kinematics::{AnalyticIkOptions, ArmKind, EndFrame, Pose};

/// Joint-5 angles at and near the singularity \[rad\].
const NEAR_ZERO_Q5: [f64; 11] = [
    0.0, 1e-14, -1e-12, 1e-10, -1e-10, 1e-9, -1e-9, 1e-6, -1e-6, 1e-4, -1e-4,
];
/// What "reaches the pose" means here \[m, rad\].
const TOLERANCE: f64 = 1e-6;

/// The smallest FK error (position \[m\], orientation \[rad\]) over the solutions, as the larger of
/// the two, and the error of the worst solution.
fn best_and_worst(
    kind: ArmKind,
    target: &Pose,
    frame: EndFrame,
    options: &AnalyticIkOptions,
) -> Result<(f64, f64, bool), String> {
    let model = kind.model();
    let solutions = model
        .ik_analytic(target, frame, options)
        .map_err(|e| e.to_string())?;
    let errors: Vec<f64> = solutions
        .iter()
        .map(|s| {
            let (dp, dr) = model.fk(&s.joints, frame).distance_to(target);
            dp.max(dr)
        })
        .collect();
    let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
    let worst = errors.iter().copied().fold(0.0, f64::max);
    Ok((best, worst, solutions.iter().any(|s| s.in_limits)))
}

#[test]
fn the_reported_pose_with_joint_5_at_zero_is_reached_not_out_of_reach() {
    // `fairgrasp fk --joints 1 -1 0.3 -1 0 1`, then `fairgrasp ik` on that flange pose with the
    // default --current (all zero, so the preferred θ6 is 0 while the pose has θ6 = 1).
    let model = ArmKind::Fr3.model();
    let q = [1.0, -1.0, 0.3, -1.0, 0.0, 1.0];
    let target = model.fk_flange(&q);
    let (best, _, any_in_limits) = best_and_worst(
        ArmKind::Fr3,
        &target,
        EndFrame::Flange,
        &AnalyticIkOptions::default(),
    )
    .unwrap();
    assert!(best < 1e-9, "best solution misses by {best:e}");
    assert!(any_in_limits);
}

#[test]
fn ik_of_the_fk_pose_reaches_it_when_joint_5_is_zero_or_nearly_zero() {
    let mut rng = common::rng(15);
    let mut worst_best = 0.0_f64;
    let mut worst_any = 0.0_f64;
    for kind in [ArmKind::Fr3, ArmKind::Fr5] {
        let model = kind.model();
        for n in 0..3_000 {
            let mut q = common::random_in_limits(&model, &mut rng);
            q[4] = NEAR_ZERO_Q5[n % NEAR_ZERO_Q5.len()];
            let frame = if n % 2 == 0 {
                EndFrame::Flange
            } else {
                EndFrame::Tcp
            };
            let target = model.fk(&q, frame);
            // The preferred θ6 alternates between 0 (the CLI's default) and an arbitrary value.
            let options = AnalyticIkOptions {
                wrist_singular_q6: if n % 3 == 0 {
                    0.0
                } else {
                    2.5 - n as f64 * 1e-3
                },
                ..Default::default()
            };
            let (best, worst, _) = best_and_worst(kind, &target, frame, &options)
                .unwrap_or_else(|e| panic!("{kind:?} sample {n}: q = {q:?}: {e}"));
            assert!(
                best <= TOLERANCE,
                "{kind:?} sample {n}: q = {q:?}: the best solution misses by {best:e}"
            );
            worst_best = worst_best.max(best);
            worst_any = worst_any.max(worst);
        }
    }
    // Every returned branch is a solution, not only the best one.
    assert!(
        worst_any <= TOLERANCE,
        "some branch misses by {worst_any:e}"
    );
    eprintln!("worst best-branch error {worst_best:e}, worst branch error {worst_any:e}");
}

#[test]
fn seeded_with_the_original_joints_the_nearest_branch_is_the_original_configuration() {
    // At θ5 = 0 the seed's θ6 is kept; from |θ5| = 1e-6 on, θ6 is read from the pose to about
    // 1e-16 / |sin θ5| rad. In between (1e-14 … 1e-9) the pose, not the joints, is recovered:
    // the test above covers it.
    const RECOVERABLE_Q5: [f64; 5] = [0.0, 1e-6, -1e-6, 1e-4, -1e-4];
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(16);
    for n in 0..2_000 {
        let mut q = common::random_in_limits(&model, &mut rng);
        q[4] = RECOVERABLE_Q5[n % RECOVERABLE_Q5.len()];
        let target = model.fk_tcp(&q);
        let nearest = model
            .ik_nearest(&target, EndFrame::Tcp, &q)
            .unwrap_or_else(|e| panic!("sample {n}: q = {q:?}: {e}"))
            .unwrap_or_else(|| panic!("sample {n}: q = {q:?}: no in-limit branch"));
        let difference = common::max_abs_diff(&nearest.joints, &q);
        assert!(
            difference < TOLERANCE,
            "sample {n}: q = {q:?}, nearest {:?} ({difference:e} rad away)",
            nearest.joints
        );
    }
}

#[test]
fn with_the_default_preferred_q6_an_in_limit_branch_is_found_at_a_singular_wrist() {
    let model = ArmKind::Fr3.model();
    let mut rng = common::rng(17);
    let mut without = 0;
    for n in 0..2_000 {
        let mut q = common::random_in_limits(&model, &mut rng);
        q[4] = NEAR_ZERO_Q5[n % 5];
        let target = model.fk_flange(&q);
        let (_, _, any_in_limits) = best_and_worst(
            ArmKind::Fr3,
            &target,
            EndFrame::Flange,
            &AnalyticIkOptions::default(),
        )
        .unwrap();
        without += usize::from(!any_in_limits);
    }
    assert_eq!(
        without, 0,
        "{without} of 2000 poses without an in-limit branch"
    );
}
