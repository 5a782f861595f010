//! The packed poses decoded as the page decodes them, against the recorded ones.

use std::io::Read;

use fairgrasp_types::trajectory::{TrajectoryRow, TrajectoryScene};

use super::*;

/// The page's decoding, in Rust: inflate, join the planes, un-zigzag, sum the differences.
fn decode(packed: &Packed) -> Vec<i16> {
    let mut planes = Vec::new();
    flate2::read::GzDecoder::new(&packed.poses_gz[..])
        .read_to_end(&mut planes)
        .unwrap();
    let n = planes.len() / 2;
    assert_eq!(n, packed.values);
    (0..n)
        .map(|i| {
            let z = u16::from(planes[i]) | (u16::from(planes[n + i]) << 8);
            ((z >> 1) as i16) ^ -((z & 1) as i16)
        })
        .collect()
}

#[test]
fn packed_poses_decode_to_the_recorded_ones_within_the_quantum() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let rows: Vec<TrajectoryRow> = (0..5)
        .map(|i| {
            let x = 0.3 + 0.01 * i as f64;
            let turn = if i % 2 == 0 { 1.0 } else { -1.0 }; // q and −q: the same rotation
            TrajectoryRow {
                step: i,
                time_s: i as f64 / 12.0,
                joints: [0.0; 6],
                gripper_opening_m: 0.08,
                tcp_xyz: [x, 0.0, 0.2],
                tcp_quat_xyzw: [0.0, 0.0, 0.0, 1.0],
                object_xyz: [0.35, -0.05, 0.025],
                object_quat_xyzw: [0.0, 0.0, 0.0, 1.0],
                action: [0.0; 7],
                reward: -0.1 * i as f64,
                capsules: vec![],
                bodies: vec![[x, -1.5, 2.0 * x, 0.0, 0.0, turn * s, turn * s]],
                pad_contact: [i > 2, i > 3],
                events: vec![],
                phase: Some("approach".into()),
            }
        })
        .collect();
    let t = Trajectory {
        scene: TrajectoryScene {
            bodies: vec!["palm".into()],
            ..TrajectoryScene::default()
        },
        rows,
        outcome: Some(fairgrasp_types::Outcome::Success),
    };
    let e = ReplayEpisode {
        method: "m".into(),
        preset: "p".into(),
        episode: 0,
        outcome: None,
        trajectory: &t,
    };
    let packed = pack(&[e.clone(), e]).unwrap();
    let values = decode(&packed);
    let episodes = packed.index["episodes"].as_array().unwrap();
    assert_eq!(
        episodes[1]["offset"].as_u64().unwrap() as usize,
        values.len() / 2
    );
    assert_eq!(episodes[0]["outcome"], "success");
    assert_eq!(episodes[0]["contacts"], serde_json::json!([0, 0, 0, 1, 3]));
    // Track 0 (the body), component k, step i at offset (0 · 7 + k) · 5 + i: summed.
    let series = |k: usize| -> Vec<f64> {
        let mut acc = 0i16;
        (0..5)
            .map(|i| {
                acc = acc.wrapping_add(values[k * 5 + i]);
                f64::from(acc)
            })
            .collect()
    };
    for (i, row) in t.rows.iter().enumerate() {
        let p = row.bodies[0];
        for (k, recorded) in p.iter().enumerate().take(3) {
            assert!((series(k)[i] * POSITION_STEP - recorded).abs() <= 0.5 * POSITION_STEP);
        }
        // The sign flips of the recorded quaternion are undone: w stays positive.
        assert!(
            (series(6)[i] / QUAT_SCALE - s).abs() < 1e-4,
            "{:?}",
            series(6)
        );
    }
}
