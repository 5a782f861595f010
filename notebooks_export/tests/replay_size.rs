//! The 3D replay of a 20-episode comparison stays under 5 MB: twelve methods (the four scripts
//! and eight learned policies, as `fairgrasp compare` runs by default) on 20 scenarios, every
//! episode the longest there is (200 steps, a timeout), ten bodies moving at every step.

use fairgrasp_report::replay3d::{ReplayEpisode, replay_html};
use fairgrasp_types::body::{BodyShape, Geometry};
use fairgrasp_types::trajectory::{Trajectory, TrajectoryRow, TrajectoryScene};

/// A 200-step episode whose ten bodies all move smoothly (seeded by `k`).
fn long_episode(k: usize) -> Trajectory {
    let bodies: Vec<String> = (0..10).map(|b| format!("body{b}")).collect();
    let shapes = (0..10)
        .map(|b| BodyShape {
            name: format!("body{b}"),
            body: b,
            geometry: Geometry::Capsule {
                a: [0.0; 3],
                b: [0.0, 0.0, 0.1],
                radius: 0.05,
            },
        })
        .collect();
    let rows = (0..=200)
        .map(|i| {
            let t = i as f64 / 12.0;
            let phase = k as f64 * 0.37;
            let pose = |b: usize| {
                let w = 0.4 + 0.05 * b as f64;
                let a = 0.5 * (w * t + phase).sin();
                let (s, c) = (0.5 * a).sin_cos();
                [
                    0.3 * (w * t + phase).cos(),
                    0.3 * (w * t + phase).sin(),
                    0.2 + 0.05 * b as f64 + 0.1 * (0.7 * w * t).sin(),
                    0.0,
                    s * 0.6,
                    s * 0.8,
                    c,
                ]
            };
            let p = pose(9);
            TrajectoryRow {
                step: i,
                time_s: t,
                joints: [0.0; 6],
                gripper_opening_m: 0.05,
                tcp_xyz: [p[0], p[1], p[2]],
                tcp_quat_xyzw: [p[3], p[4], p[5], p[6]],
                object_xyz: [0.35, 0.0, 0.025 + 0.001 * i as f64],
                object_quat_xyzw: [0.0, 0.0, 0.0, 1.0],
                action: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, (0.1 * t).sin()],
                reward: -0.01 * t,
                capsules: Vec::new(),
                bodies: (0..10).map(pose).collect(),
                pad_contact: [i > 100, i > 110],
                events: Vec::new(),
                phase: Some(["approach", "descend", "close", "lift"][i / 60].into()),
            }
        })
        .collect();
    Trajectory {
        scene: TrajectoryScene {
            cube_size: 0.05,
            bodies,
            shapes,
            ..TrajectoryScene::default()
        },
        rows,
        outcome: Some(fairgrasp_types::Outcome::Timeout),
    }
}

#[test]
fn a_20_episode_report_with_twelve_methods_fits_in_5_mb() {
    let trajectories: Vec<Trajectory> = (0..20).map(long_episode).collect();
    let episodes: Vec<ReplayEpisode<'_>> = (0..12)
        .flat_map(|m| {
            trajectories
                .iter()
                .enumerate()
                .map(move |(k, t)| ReplayEpisode {
                    method: format!("method {m}"),
                    preset: "wrist_camera".into(),
                    episode: k,
                    outcome: None,
                    trajectory: t,
                })
        })
        .collect();
    let html = replay_html("size", &episodes).unwrap();
    eprintln!("240 episodes × 201 steps: {} bytes", html.len());
    assert!(html.len() < 5_000_000, "{} bytes", html.len());
    assert!(
        html.contains("three.js authors"),
        "three.js's licence is kept"
    );
}
