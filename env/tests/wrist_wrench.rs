//! Physical facts of the six-axis wrist sensor (`Observation::wrist_force`, `wrist_torque`):
//! a held cube in the air reads nothing once tared; a cube held off the sensor's axis and
//! pressed flat on the table reads the torque `M = r × F` of the table's push at the cube's
//! bottom face, and the centre of pressure computed from the reading is where the cube stands;
//! dragged along the table, the friction is read as a lateral force against the motion.
//! The sensor's noise is off here and it reads the friction (`[sensor.wrench]` all zero,
//! `friction = true`): these are facts of the truth.

mod common;

use common::{drive, grasp_targets};
use fairgrasp_env::config::WrenchSensorConfig;
use fairgrasp_env::sensor::Wrench;
use fairgrasp_env::{EnvConfig, Observation, TaskEnv, TaskKind};
use fairgrasp_kinematics::EndFrame;

/// A place env whose pocket stands 20 cm from the cube, every step simulated, a noiseless
/// sensor.
fn noiseless_place() -> EnvConfig {
    let mut cfg = EnvConfig::default();
    cfg.task.kind = TaskKind::Place;
    cfg.task.max_steps = 400;
    cfg.task.place.fixture_xy = [0.30, 0.20];
    cfg.physics.free_space = false;
    cfg.sensor.wrench = Some(WrenchSensorConfig {
        force_noise: 0.0,
        torque_noise: 0.0,
        force_resolution: 0.0,
        torque_resolution: 0.0,
        friction: true,
    });
    cfg
}

/// The joints that put the TCP at `grasp`'s pose moved by `offset` \[m\] in `base_link`.
fn moved(env: &TaskEnv, joints: &[f64; 6], offset: [f64; 3]) -> [f64; 6] {
    let mut pose = env.model().fk_tcp(joints);
    for (i, d) in offset.iter().enumerate() {
        pose.iso.translation.vector[i] += d;
    }
    env.model()
        .ik_nearest(&pose, EndFrame::Tcp, joints)
        .expect("valid pose")
        .expect("reachable")
        .joints
}

/// Grasps the cube with the TCP `along_pads` \[m\] off its centre along the pads' faces (the
/// TCP's y), lifts it 3 cm and holds it still; returns the env, the lifted joints and the
/// last observation.
fn grasp_off_centre(along_pads: f64) -> (TaskEnv, [f64; 6], Observation) {
    let mut env = TaskEnv::new(noiseless_place()).unwrap();
    env.reset(0).unwrap();
    let (grasp, pre) = grasp_targets(&env);
    let tcp = env.model().fk_tcp(&grasp);
    let shift = tcp.transform_vector([along_pads, 0.0, 0.0]);
    let (grasp, pre) = (moved(&env, &grasp, shift), moved(&env, &pre, shift));
    drive(&mut env, pre, -1.0, 40);
    drive(&mut env, grasp, -1.0, 40);
    drive(&mut env, grasp, 1.0, 20);
    let lifted = moved(&env, &grasp, [0.0, 0.0, 0.03]);
    let step = drive(&mut env, lifted, 1.0, 40);
    assert!(
        step.obs.pad_contact == [true, true],
        "the cube is not held: {:?}",
        step.obs
    );
    (env, lifted, step.obs)
}

fn norm(v: [f64; 3]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[test]
fn a_held_cube_in_the_air_reads_no_force_and_no_torque_once_tared() {
    let (_, _, obs) = grasp_off_centre(0.0);
    let w = obs.wrist_wrench().expect("a place env has the sensor");
    assert!(norm(w.force) < 0.05, "force in the air: {:?} N", w.force);
    assert!(
        norm(w.torque) < 0.005,
        "torque in the air: {:?} N·m",
        w.torque
    );
}

/// Lowers the lifted cube in 0.5 mm steps until the sensor reads at least `press` \[N\] up,
/// then holds; returns the env, the joints it holds and the held reading.
fn press_on_table(along_pads: f64, press: f64) -> (TaskEnv, [f64; 6], Wrench) {
    let (mut env, lifted, _) = grasp_off_centre(along_pads);
    for k in 1..200 {
        let target = moved(&env, &lifted, [0.0, 0.0, -0.0005 * k as f64]);
        let step = drive(&mut env, target, 1.0, 2);
        let w = step.obs.wrist_wrench().unwrap();
        if w.force[2] >= press {
            let held = drive(&mut env, target, 1.0, 3).obs.wrist_wrench().unwrap();
            return (env, target, held);
        }
    }
    panic!("the cube never pressed on the table with {press} N");
}

/// The cube's corners the table touches \[m, `base_link`\]: those within 0.3 mm of the lowest
/// (one corner, an edge's two ends, or the bottom face's four).
fn touching_corners(env: &TaskEnv) -> Vec<[f64; 3]> {
    let half = 0.5 * env.config().scene.cube_size;
    let cube = env.object_in_base();
    let corners: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            cube.transform_point([0, 1, 2].map(|i| if k >> i & 1 == 0 { -half } else { half }))
        })
        .collect();
    let lowest = corners.iter().map(|c| c[2]).fold(f64::INFINITY, f64::min);
    corners
        .into_iter()
        .filter(|c| c[2] < lowest + 3e-4)
        .collect()
}

/// The point of the segment `a`–`b` nearest to `p` (all `[x, y, z]`).
fn nearest_on_segment(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> [f64; 3] {
    let d = [0, 1, 2].map(|i| b[i] - a[i]);
    let dd: f64 = d.iter().map(|x| x * x).sum();
    let t = if dd > 0.0 {
        ([0, 1, 2].map(|i| (p[i] - a[i]) * d[i]).iter().sum::<f64>() / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [0, 1, 2].map(|i| a[i] + t * d[i])
}

/// A press off the sensor's axis: the cube held `along` \[m\] off the TCP along its x and pressed
/// with 5 N lands on one bottom edge (it hangs a degree tilted); the reading, the flange and the
/// edge's ends.
fn edge_press(along: f64) -> (Wrench, [f64; 3], [[f64; 3]; 2]) {
    let (env, joints, w) = press_on_table(along, 5.0);
    let flange = env.model().fk_flange(&joints).xyz();
    let corners = touching_corners(&env);
    assert_eq!(corners.len(), 2, "not an edge on the table: {corners:?}");
    (w, flange, [corners[0], corners[1]])
}

#[test]
fn a_press_off_the_sensor_axis_reads_the_bending_torque_r_cross_f_of_the_push_on_the_touching_edge()
{
    for along in [-0.008, 0.008] {
        let (w, flange, [a, b]) = edge_press(along);
        // The pressure along an edge is spread as the solver finds it: the bending torque (about
        // the horizontal axes, what the centre of pressure is read from) must be r × F's for some
        // point r of the edge. The torque about the vertical leaves out the solver's twist
        // friction (`wrist_wrench`'s comment).
        let (error, expected, r) = (0..=100)
            .map(|k| {
                let p = [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * k as f64 / 100.0);
                let r = [0, 1, 2].map(|i| p[i] - flange[i]);
                let f = w.force;
                let m = [
                    r[1] * f[2] - r[2] * f[1],
                    r[2] * f[0] - r[0] * f[2],
                    r[0] * f[1] - r[1] * f[0],
                ];
                let bending = |v: [f64; 3]| [v[0], v[1], 0.0];
                (
                    norm(bending([0, 1, 2].map(|i| w.torque[i] - m[i]))),
                    bending(m),
                    r,
                )
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .unwrap();
        let offset = (r[0] * r[0] + r[1] * r[1]).sqrt();
        assert!(
            offset > 0.01,
            "the press is only {offset} m off the sensor's axis"
        );
        assert!(
            error <= 0.05 * norm(expected),
            "{along} m off: torque {:?} N·m, nearest r × F on the edge = {expected:?} (r = {r:?} m, F = {:?} N)",
            w.torque,
            w.force
        );
    }
}

#[test]
fn the_centre_of_pressure_of_a_5_newton_press_lies_on_the_edge_the_cube_touches() {
    for along in [-0.008, 0.0, 0.008] {
        let (w, flange, [a, b]) = edge_press(along);
        let depth = flange[2] - 0.5 * (a[2] + b[2]);
        let [x, y] = w.centre_of_pressure(depth, 1.0).expect("a press");
        let cop = [flange[0] + x, flange[1] + y, 0.5 * (a[2] + b[2])];
        let on_edge = nearest_on_segment(a, b, cop);
        let miss = norm([0, 1, 2].map(|i| cop[i] - on_edge[i]));
        assert!(
            miss < 0.001,
            "{along} m off: centre of pressure {cop:?}, {miss} m from the touching edge {a:?}–{b:?}"
        );
    }
}

#[test]
fn dragging_the_pressed_cube_along_the_table_reads_its_friction_against_the_motion() {
    let (mut env, joints, before) = press_on_table(0.0, 3.0);
    // Drag 6 mm along base x at about 1 cm/s.
    let mut lateral: f64 = 0.0;
    for k in 1..=12 {
        let target = moved(&env, &joints, [0.0005 * k as f64, 0.0, 0.0]);
        let w = drive(&mut env, target, 1.0, 1).obs.wrist_wrench().unwrap();
        lateral = lateral.min(w.force[0]);
    }
    // The table's friction on the cube points against the motion (−x), a good part of μ·F_z.
    assert!(
        lateral < -0.5,
        "lateral force while dragging: {lateral} N (pressed with {:?} N)",
        before.force
    );
}
