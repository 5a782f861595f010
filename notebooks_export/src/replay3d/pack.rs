//! The replay's data: a JSON index (per episode its labels, outcome, scene, shapes and the
//! timeline's per-step values) and the poses of every moving thing, packed small.
//!
//! Poses are quantised to 16-bit integers (positions in 0.1 mm, quaternion components in
//! 1/30 000), laid out per episode as track × component × step, differenced along the steps,
//! zigzag-coded and split into a low-byte and a high-byte plane, then gzipped: the browser
//! inflates them with its own `DecompressionStream` and sums the differences back.

use std::io::Write;

use fairgrasp_types::body::{BodyShape, Geometry, IDENTITY_POSE, Pose7};
use fairgrasp_types::trajectory::Trajectory;
use serde::Serialize;
use serde_json::{Value, json};

use crate::replay3d::episode::ReplayEpisode;

/// Position quantum \[m\].
pub const POSITION_STEP: f64 = 1e-4;
/// Quaternion component scale (1.0 ↦ this).
pub const QUAT_SCALE: f64 = 30_000.0;

/// The packed episodes: the index (JSON) and the gzipped pose planes.
pub struct Packed {
    pub index: Value,
    pub poses_gz: Vec<u8>,
    /// Number of 16-bit values in the pose planes.
    pub values: usize,
}

/// The bodies of an episode: names, shapes and per-step poses in `base_link`. Trajectories
/// recorded before body poses were (capsules only) get one body per capsule.
struct Bodies {
    names: Vec<String>,
    shapes: Vec<BodyShape>,
    /// `poses[step][body]`.
    poses: Vec<Vec<Pose7>>,
}

fn bodies_of(t: &Trajectory) -> Bodies {
    if !t.scene.bodies.is_empty() {
        return Bodies {
            names: t.scene.bodies.clone(),
            shapes: t.scene.shapes.clone(),
            poses: t.rows.iter().map(|r| r.bodies.clone()).collect(),
        };
    }
    // Older files: each capsule [a, b, radius] becomes a body at its midpoint, z along a → b.
    let first = &t.rows[0].capsules;
    let shapes = first
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let half = 0.5
                * ((c[3] - c[0]).powi(2) + (c[4] - c[1]).powi(2) + (c[5] - c[2]).powi(2)).sqrt();
            BodyShape {
                name: t.scene.capsule_names.get(i).cloned().unwrap_or_default(),
                body: i,
                geometry: Geometry::Capsule {
                    a: [0.0, 0.0, -half],
                    b: [0.0, 0.0, half],
                    radius: c[6],
                },
            }
        })
        .collect();
    let poses = t
        .rows
        .iter()
        .map(|r| r.capsules.iter().map(capsule_pose).collect())
        .collect();
    Bodies {
        names: t.scene.capsule_names.clone(),
        shapes,
        poses,
    }
}

/// A pose at the capsule's midpoint whose z axis points from `a` to `b`.
fn capsule_pose(c: &[f64; 7]) -> Pose7 {
    let d = [c[3] - c[0], c[4] - c[1], c[5] - c[2]];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let mid = [
        0.5 * (c[0] + c[3]),
        0.5 * (c[1] + c[4]),
        0.5 * (c[2] + c[5]),
    ];
    if len < 1e-12 {
        return [mid[0], mid[1], mid[2], 0.0, 0.0, 0.0, 1.0];
    }
    let u = d.map(|v| v / len);
    // The shortest rotation taking z = (0, 0, 1) to u: axis z × u, half-angle form.
    let w = 1.0 + u[2];
    let q = if w < 1e-9 {
        [1.0, 0.0, 0.0, 0.0]
    } else {
        let n = (u[1] * u[1] + u[0] * u[0] + w * w).sqrt();
        [-u[1] / n, u[0] / n, 0.0, w / n]
    };
    [mid[0], mid[1], mid[2], q[0], q[1], q[2], q[3]]
}

/// `p` with its quaternion's sign chosen to continue `previous`'s (q and −q are the same
/// rotation; a sign flip between two steps would interpolate through a full turn).
fn continuing(p: &Pose7, previous: Option<&Pose7>) -> Pose7 {
    let flip = previous.is_some_and(|q| (3..7).map(|k| p[k] * q[k]).sum::<f64>() < 0.0);
    let sign = if flip { -1.0 } else { 1.0 };
    std::array::from_fn(|k| if k < 3 { p[k] } else { sign * p[k] })
}

/// A pose's quantised components: position in [`POSITION_STEP`]s, quaternion × [`QUAT_SCALE`].
fn quantise(p: &Pose7) -> [i16; 7] {
    std::array::from_fn(|k| {
        let v = if k < 3 {
            p[k] / POSITION_STEP
        } else {
            p[k] * QUAT_SCALE
        };
        v.round().clamp(-32_767.0, 32_767.0) as i16
    })
}

/// Rounds to `digits` decimals (JSON stays short).
fn round(v: f64, digits: i32) -> f64 {
    let s = 10f64.powi(digits);
    if v.is_finite() {
        (v * s).round() / s
    } else {
        0.0
    }
}

#[derive(Serialize)]
struct ShapeJson<'a> {
    name: &'a str,
    body: usize,
    #[serde(flatten)]
    geometry: &'a Geometry,
}

/// The index entry and the (differenced) pose values of one episode; `offset` is where its
/// values start in the whole stream.
fn pack_episode(e: &ReplayEpisode<'_>, offset: usize, values: &mut Vec<i16>) -> Value {
    let t = e.trajectory;
    let bodies = bodies_of(t);
    // Tracks: the bodies, the cube, the TCP.
    let tracks: Vec<Vec<Pose7>> = (0..bodies.names.len())
        .map(|b| bodies.poses.iter().map(|p| p[b]).collect())
        .chain([t
            .rows
            .iter()
            .map(|r| {
                let (p, q) = (r.object_xyz, r.object_quat_xyzw);
                [p[0], p[1], p[2], q[0], q[1], q[2], q[3]]
            })
            .collect()])
        .chain([t
            .rows
            .iter()
            .map(|r| {
                let (p, q) = (r.tcp_xyz, r.tcp_quat_xyzw);
                let q = if q == [0.0; 4] {
                    [0.0, 0.0, 0.0, 1.0]
                } else {
                    q
                };
                [p[0], p[1], p[2], q[0], q[1], q[2], q[3]]
            })
            .collect()])
        .collect();
    for track in &tracks {
        let mut previous: Option<Pose7> = None;
        let quantised: Vec<[i16; 7]> = track
            .iter()
            .map(|p| {
                let kept = continuing(p, previous.as_ref());
                previous = Some(kept);
                quantise(&kept)
            })
            .collect();
        for k in 0..7 {
            let mut last = 0i16;
            for q in &quantised {
                values.push(q[k].wrapping_sub(last));
                last = q[k];
            }
        }
    }
    let steps = t.rows.len();
    let dt = if steps > 1 {
        t.rows[1].time_s - t.rows[0].time_s
    } else {
        0.0
    };
    // Phases as runs: [first step, name].
    let mut phases: Vec<(usize, String)> = Vec::new();
    for (i, r) in t.rows.iter().enumerate() {
        let name = r.phase.clone().unwrap_or_default();
        if phases.last().is_none_or(|(_, p)| *p != name) {
            phases.push((i, name));
        }
    }
    let events: Vec<(usize, &String)> = t
        .rows
        .iter()
        .enumerate()
        .flat_map(|(i, r)| r.events.iter().map(move |e| (i, e)))
        .collect();
    let scene = &t.scene;
    let shapes: Vec<ShapeJson<'_>> = bodies
        .shapes
        .iter()
        .map(|s| ShapeJson {
            name: &s.name,
            body: s.body,
            geometry: &s.geometry,
        })
        .collect();
    let outcome = e.outcome.or(t.outcome);
    json!({
        "method": e.method,
        "preset": e.preset,
        "episode": e.episode,
        "outcome": outcome.map(|o| o.as_str()),
        "steps": steps,
        "dt": dt,
        "offset": offset,
        "bodies": bodies.names,
        "shapes": shapes,
        "cube": scene.cube_size,
        "base": if scene.base_in_world == [0.0; 7] { IDENTITY_POSE } else { scene.base_in_world },
        "table": scene.table_in_world,
        "tableCorners": scene.table_corners_xy,
        "tableTopZ": scene.table_top_z,
        "reward": t.rows.iter().map(|r| round(r.reward, 4)).collect::<Vec<_>>(),
        "gripper": t.rows.iter().map(|r| round(r.action[6], 3)).collect::<Vec<_>>(),
        "contacts": t.rows.iter().map(|r| u8::from(r.pad_contact[0]) + 2 * u8::from(r.pad_contact[1])).collect::<Vec<_>>(),
        "phases": phases,
        "events": events,
    })
}

/// Packs `episodes` for the page.
pub fn pack(episodes: &[ReplayEpisode<'_>]) -> std::io::Result<Packed> {
    let mut values: Vec<i16> = Vec::new();
    let mut index = Vec::with_capacity(episodes.len());
    for e in episodes {
        let offset = values.len();
        index.push(pack_episode(e, offset, &mut values));
    }
    // Zigzag, then the low bytes of every value followed by the high bytes.
    let zigzag: Vec<u16> = values
        .iter()
        .map(|&v| ((v << 1) ^ (v >> 15)) as u16)
        .collect();
    let mut planes = Vec::with_capacity(2 * zigzag.len());
    planes.extend(zigzag.iter().map(|z| (z & 0xff) as u8));
    planes.extend(zigzag.iter().map(|z| (z >> 8) as u8));
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(&planes)?;
    Ok(Packed {
        index: json!({
            "positionStep": POSITION_STEP,
            "quatScale": QUAT_SCALE,
            "episodes": index,
        }),
        poses_gz: gz.finish()?,
        values: values.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_pose_puts_its_z_axis_along_the_segment() {
        use fairgrasp_types::body::rotate;
        for c in [
            [0.0, 0.0, 0.0, 0.0, 0.0, 0.3, 0.05],
            [0.1, 0.2, 0.3, 0.4, -0.1, 0.3, 0.05],
            [0.0, 0.0, 0.0, 0.0, 0.0, -0.2, 0.05],
        ] {
            let p = capsule_pose(&c);
            let z = rotate([p[3], p[4], p[5], p[6]], [0.0, 0.0, 1.0]);
            let d = [c[3] - c[0], c[4] - c[1], c[5] - c[2]];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            for k in 0..3 {
                assert!((z[k] - d[k] / len).abs() < 1e-9, "{c:?}: {z:?}");
                assert!((p[k] - 0.5 * (c[k] + c[k + 3])).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn quantised_quaternions_keep_their_sign_continuous() {
        let a = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
        let b = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0];
        assert_eq!(quantise(&continuing(&b, Some(&a)))[6], 30_000);
        assert_eq!(quantise(&continuing(&b, None))[6], -30_000);
        assert_eq!(
            quantise(&[1.0, -2.0, 0.00005, 0.0, 0.0, 0.0, 1.0])[..3],
            [10_000, -20_000, 1]
        );
    }
}

#[cfg(test)]
#[path = "pack_decode_tests.rs"]
mod decode_tests;
