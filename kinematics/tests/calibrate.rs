//! Calibration on synthetic cells with known answers: exact data gives the answer to 1e-9;
//! measurement noise of a careful touch (±1 mm per axis) or of a marker detector (±1 mm, ±0.2°)
//! stays within the bounds asserted here; too few, collinear, single-axis, unit-mistaken and
//! mistyped measurements are refused, naming the problem.

use fairgrasp_kinematics::calibrate::{
    CalibrationError, HandEyeOptions, HandEyeSample, PointFitOptions, PointPair, fit_eye_to_hand,
    fit_points,
};
use fairgrasp_kinematics::{ArmKind, Pose};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_pose(rng: &mut ChaCha8Rng, reach: f64, tilt: f64) -> Pose {
    Pose::from_xyz_rpy(
        [0; 3].map(|_| rng.random_range(-reach..reach)),
        [
            rng.random_range(-tilt..tilt),
            rng.random_range(-tilt..tilt),
            rng.random_range(-std::f64::consts::PI..std::f64::consts::PI),
        ],
    )
}

fn noise(rng: &mut ChaCha8Rng, size: f64) -> [f64; 3] {
    [0; 3].map(|_| size * rng.random_range(-1.0..1.0))
}

/// Touches of the FR3's TCP at random joint readings, with their world points for `mount`.
fn touches(rng: &mut ChaCha8Rng, mount: &Pose, n: usize, touch_noise: f64) -> Vec<PointPair> {
    let fr3 = ArmKind::Fr3.model();
    (0..n)
        .map(|_| {
            let q = [
                rng.random_range(-1.5..1.5),
                rng.random_range(-2.0..-0.8),
                rng.random_range(0.8..2.0),
                rng.random_range(-2.0..-1.0),
                -1.57,
                0.0,
            ];
            let base = fr3.fk_tcp(&q).xyz();
            let e = noise(rng, touch_noise);
            let w = mount.transform_point(base);
            PointPair {
                world: [w[0] + e[0], w[1] + e[1], w[2] + e[2]],
                base,
            }
        })
        .collect()
}

#[test]
fn exact_touches_give_the_mount_to_1e_9() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..50 {
        let mount = random_pose(&mut rng, 1.0, 0.26);
        let pairs = touches(&mut rng, &mount, 5, 0.0);
        let fit = fit_points(&pairs, &PointFitOptions::default()).unwrap();
        let (dp, dr) = fit.base_in_world.distance_to(&mount);
        assert!(dp < 1e-9 && dr < 1e-9, "{dp} {dr}");
        assert!(fit.rms < 1e-9 && (fit.scale - 1.0).abs() < 1e-9);
    }
}

#[test]
fn one_millimetre_touches_give_the_mount_within_2_mm_and_0_3_degrees() {
    // 8 touches spread over the FR3's workspace, each off by up to ±1 mm per axis.
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let (mut worst_p, mut worst_r) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let mount = random_pose(&mut rng, 1.0, 0.26);
        let pairs = touches(&mut rng, &mount, 8, 0.001);
        let fit = fit_points(&pairs, &PointFitOptions::default()).unwrap();
        let (dp, dr) = fit.base_in_world.distance_to(&mount);
        (worst_p, worst_r) = (worst_p.max(dp), worst_r.max(dr));
        // The refinement never makes the closed form worse; both are the same optimum.
        assert!(fit.rms <= fit.closed_form_rms + 1e-12);
        assert!(fit.rms < 0.0015, "rms {}", fit.rms);
    }
    eprintln!(
        "worst of 200: {:.2} mm, {:.3}°",
        worst_p * 1e3,
        worst_r.to_degrees()
    );
    assert!(worst_p < 0.002, "{worst_p}");
    assert!(worst_r < 0.3f64.to_radians(), "{}", worst_r.to_degrees());
}

#[test]
fn too_few_collinear_millimetres_and_a_mistyped_point_are_refused() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mount = random_pose(&mut rng, 1.0, 0.2);
    let opts = PointFitOptions::default();
    let pairs = touches(&mut rng, &mount, 6, 0.0);

    let err = fit_points(&pairs[..2], &opts).unwrap_err();
    assert!(
        matches!(
            err,
            CalibrationError::TooFew {
                found: 2,
                needed: 3,
                ..
            }
        ),
        "{err}"
    );

    let line: Vec<PointPair> = (0..5)
        .map(|k| {
            let base = [0.3 + 0.05 * k as f64, 0.1, 0.2];
            PointPair {
                world: mount.transform_point(base),
                base,
            }
        })
        .collect();
    let err = fit_points(&line, &opts).unwrap_err();
    assert!(err.to_string().contains("one line"), "{err}");

    // World points typed in millimetres, base points in metres.
    let mm: Vec<PointPair> = pairs
        .iter()
        .map(|p| PointPair {
            world: p.world.map(|v| v * 1000.0),
            base: p.base,
        })
        .collect();
    let err = fit_points(&mm, &opts).unwrap_err();
    assert!(
        matches!(err, CalibrationError::ScaleMismatch { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("metres"), "{err}");

    // Point 4's world z mistyped by 3 cm: refused naming point 4.
    let mut typo = pairs.clone();
    typo[3].world[2] += 0.03;
    let err = fit_points(&typo, &opts).unwrap_err();
    match &err {
        CalibrationError::ResidualTooLarge { index, .. } => assert_eq!(*index, 4, "{err}"),
        other => panic!("expected a residual refusal, got {other}"),
    }

    let mut nan = pairs.clone();
    nan[1].base[0] = f64::NAN;
    let err = fit_points(&nan, &opts).unwrap_err();
    assert_eq!(
        err,
        CalibrationError::NonFinite {
            what: "point pair",
            index: 2
        }
    );
}

#[test]
fn three_or_nearly_collinear_points_warn() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mount = random_pose(&mut rng, 1.0, 0.2);
    let three = touches(&mut rng, &mount, 3, 0.0);
    let fit = fit_points(&three, &PointFitOptions::default()).unwrap();
    assert!(
        fit.warnings.iter().any(|w| w.contains("three points")),
        "{:?}",
        fit.warnings
    );

    // Five points along x, one 2 cm off the line.
    let mut base: Vec<[f64; 3]> = (0..5).map(|k| [0.2 + 0.08 * k as f64, 0.0, 0.1]).collect();
    base.push([0.35, 0.02, 0.1]);
    let pairs: Vec<PointPair> = base
        .iter()
        .map(|b| PointPair {
            world: mount.transform_point(*b),
            base: *b,
        })
        .collect();
    let fit = fit_points(&pairs, &PointFitOptions::default()).unwrap();
    assert!(
        fit.warnings
            .iter()
            .any(|w| w.contains("nearly on one line")),
        "{:?}",
        fit.warnings
    );
    assert!(fit.spread[1] < 0.05 && fit.spread[1] > 0.001);
}

/// A fixed camera `x` (in base) and a marker `y` (on the TCP): stations at random TCP poses
/// with the marker in view, the detector's error up to `pos` \[m\] and `ang` \[rad\] per axis.
fn stations(
    rng: &mut ChaCha8Rng,
    x: &Pose,
    y: &Pose,
    n: usize,
    pos: f64,
    ang: f64,
) -> Vec<HandEyeSample> {
    (0..n)
        .map(|_| {
            let g = Pose::from_xyz_rpy(
                [
                    rng.random_range(0.2..0.5),
                    rng.random_range(-0.3..0.3),
                    rng.random_range(0.05..0.4),
                ],
                [
                    std::f64::consts::PI + rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-1.5..1.5),
                ],
            );
            let c = x.inverse().compose(&g).compose(y);
            let e = noise(rng, pos);
            let r = noise(rng, ang);
            let err = Pose::from_xyz_rpy(e, r);
            HandEyeSample {
                tcp_in_base: g,
                marker_in_camera: c.compose(&err),
            }
        })
        .collect()
}

#[test]
fn hand_eye_exact_then_noisy_within_its_bounds() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let opts = HandEyeOptions::default();
    let (mut worst_p, mut worst_r) = (0.0f64, 0.0f64);
    for trial in 0..100 {
        let x = Pose::from_xyz_rpy(
            [
                rng.random_range(0.5..1.2),
                rng.random_range(-0.5..0.5),
                rng.random_range(0.5..1.0),
            ],
            [
                rng.random_range(-3.0..3.0),
                rng.random_range(-1.2..1.2),
                rng.random_range(-3.0..3.0),
            ],
        );
        let y = random_pose(&mut rng, 0.05, 3.0);
        if trial < 20 {
            let fit = fit_eye_to_hand(&stations(&mut rng, &x, &y, 6, 0.0, 0.0), &opts).unwrap();
            let (dp, dr) = fit.camera_in_base.distance_to(&x);
            assert!(dp < 1e-9 && dr < 1e-9, "{dp} {dr}");
            let (dp, dr) = fit.marker_in_tcp.distance_to(&y);
            assert!(dp < 1e-9 && dr < 1e-9, "{dp} {dr}");
            continue;
        }
        // 12 stations, the detector off by up to ±1 mm and ±0.2° per axis.
        let s = stations(&mut rng, &x, &y, 12, 0.001, 0.2f64.to_radians());
        let fit = fit_eye_to_hand(&s, &opts).unwrap();
        let (dp, dr) = fit.camera_in_base.distance_to(&x);
        (worst_p, worst_r) = (worst_p.max(dp), worst_r.max(dr));
        assert_eq!(fit.position_residuals.len(), 12);
    }
    eprintln!(
        "hand-eye, worst of 80: {:.2} mm, {:.3}°",
        worst_p * 1e3,
        worst_r.to_degrees()
    );
    // The camera is about 1 m from the markers: 0.2° of detector error is 3.5 mm there.
    assert!(worst_p < 0.006, "{worst_p}");
    assert!(worst_r < 0.25f64.to_radians(), "{}", worst_r.to_degrees());
}

#[test]
fn hand_eye_refuses_too_few_and_single_axis_stations() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let x = Pose::from_xyz_rpy([1.0, 0.0, 0.8], [0.0, 2.4, 3.1]);
    let y = Pose::from_xyz_rpy([0.0, 0.0, 0.03], [0.0, 0.0, 0.0]);
    let opts = HandEyeOptions::default();
    let err = fit_eye_to_hand(&stations(&mut rng, &x, &y, 2, 0.0, 0.0), &opts).unwrap_err();
    assert!(
        matches!(err, CalibrationError::TooFew { found: 2, .. }),
        "{err}"
    );

    // Only joint 6 turns: every motion is about the TCP's z axis.
    let fr3 = ArmKind::Fr3.model();
    let single: Vec<HandEyeSample> = (0..6)
        .map(|k| {
            let g = fr3.fk_tcp(&[0.2, -1.2, 1.4, -1.8, -1.57, 0.4 * k as f64]);
            HandEyeSample {
                tcp_in_base: g,
                marker_in_camera: x.inverse().compose(&g).compose(&y),
            }
        })
        .collect();
    let err = fit_eye_to_hand(&single, &opts).unwrap_err();
    assert!(err.to_string().contains("one axis"), "{err}");

    // A station whose marker pose was mis-read by 5 cm is named.
    let mut s = stations(&mut rng, &x, &y, 8, 0.0, 0.0);
    s[5].marker_in_camera = s[5]
        .marker_in_camera
        .compose(&Pose::from_xyz([0.05, 0.0, 0.0]));
    let err = fit_eye_to_hand(&s, &opts).unwrap_err();
    assert!(
        matches!(err, CalibrationError::ResidualTooLarge { .. }),
        "{err}"
    );
}
