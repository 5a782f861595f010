//! One recorded episode, written by the env and read by the report (one type, one schema):
//! per step the joints, gripper, TCP and object poses, action, reward, the arm's capsules, the
//! robot's body poses, the pad contacts and the policy's phase, all in `base_link` \[m\],
//! quaternions `[x, y, z, w]`; the scene says where `base_link` stands in the world. Saved as
//! CSV and JSON, or compactly as gzipped JSON with every number rounded to 1e-5 (10 µm, 10 µrad:
//! below what any chart or replay shows; `<stem>.json.gz`, what comparison folders hold). Fields
//! added after the first version have serde defaults: older files load.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::body::{BodyShape, IDENTITY_POSE, Pose7, WorldBox, rotate};
use crate::fs::write_atomic;
use crate::names::Outcome;

fn identity_quat() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

/// One recorded step; poses in `base_link`, quaternions `[x, y, z, w]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryRow {
    /// Step index (0 = the state after reset).
    #[serde(default)]
    pub step: usize,
    /// Simulated time \[s\].
    pub time_s: f64,
    pub joints: [f64; 6],
    pub gripper_opening_m: f64,
    pub tcp_xyz: [f64; 3],
    #[serde(default)]
    pub tcp_quat_xyzw: [f64; 4],
    pub object_xyz: [f64; 3],
    #[serde(default = "identity_quat")]
    pub object_quat_xyzw: [f64; 4],
    /// The action that led here (zeros for step 0).
    #[serde(default)]
    pub action: [f64; 7],
    #[serde(default)]
    pub reward: f64,
    /// The arm's and gripper's collision capsules at this step, in the order of
    /// [`TrajectoryScene::capsule_names`]: `[ax, ay, az, bx, by, bz, radius]` in `base_link` \[m\]
    /// (JSON only; for replays).
    #[serde(default)]
    pub capsules: Vec<[f64; 7]>,
    /// Pose of every body of [`TrajectoryScene::bodies`] in `base_link` (empty in files
    /// recorded before bodies were).
    #[serde(default)]
    pub bodies: Vec<Pose7>,
    /// Left and right pad touching the cube after this step.
    #[serde(default)]
    pub pad_contact: [bool; 2],
    /// What happened in this step besides motion: a collision (with the two parts), a
    /// protective stop, the cube pushed or off the table.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<String>,
    /// The policy's phase when it chose this step's action (the script's `approach`,
    /// `descend`, `close`, …; `None` for a policy without phases and for step 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<String>,
}

/// What a replay needs besides the rows: the table and cube in `base_link` \[m\].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryScene {
    /// Table top corners x, y in `base_link` (the table is axis-aligned in `world`).
    pub table_corners_xy: [[f64; 2]; 4],
    /// Table top height in `base_link`.
    pub table_top_z: f64,
    /// Cube edge length.
    pub cube_size: f64,
    /// Names of the capsules in each row (links, then palm and fingers).
    pub capsule_names: Vec<String>,
    /// `base_link` in the world (the mount: pedestal height, yaw, tilt).
    #[serde(default = "identity_pose")]
    pub base_in_world: Pose7,
    /// The table slab in the world (`None` in older files: draw it from the corners).
    #[serde(default)]
    pub table_in_world: Option<WorldBox>,
    /// Names of the rigid bodies whose poses each row records ([`TrajectoryRow::bodies`]).
    #[serde(default)]
    pub bodies: Vec<String>,
    /// The collision shapes fixed to those bodies: the simulation's own geometry.
    #[serde(default)]
    pub shapes: Vec<BodyShape>,
}

fn identity_pose() -> Pose7 {
    IDENTITY_POSE
}

/// A recorded episode.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    #[serde(default)]
    pub scene: TrajectoryScene,
    pub rows: Vec<TrajectoryRow>,
    /// How the episode ended (`None` in older files, or if recording stopped before its end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outcome: Option<Outcome>,
}

impl TrajectoryRow {
    /// The cube's 8 corners in `base_link` for edge length `size` \[m\].
    pub fn cube_corners(&self, size: f64) -> [[f64; 3]; 8] {
        let h = 0.5 * size;
        let mut out = [[0.0; 3]; 8];
        for (i, corner) in out.iter_mut().enumerate() {
            let local = [
                if i & 1 == 0 { -h } else { h },
                if i & 2 == 0 { -h } else { h },
                if i & 4 == 0 { -h } else { h },
            ];
            let r = rotate(self.object_quat_xyzw, local);
            *corner = [0, 1, 2].map(|k| self.object_xyz[k] + r[k]);
        }
        out
    }
}

impl Trajectory {
    /// Parses a trajectory's JSON text and checks it: at least one row, every row with the
    /// scene's number of capsules and of bodies, every shape on a listed body.
    pub fn from_json(text: &str) -> Result<Self, String> {
        let t: Self = serde_json::from_str(text)
            .map_err(|e| format!("not a fairgrasp trajectory JSON: {e}"))?;
        if t.rows.is_empty() {
            return Err("trajectory has no rows".into());
        }
        let n = t.scene.capsule_names.len();
        if let Some(i) = t.rows.iter().position(|r| r.capsules.len() != n) {
            return Err(format!(
                "row {i}: {} capsules, scene names {n}",
                t.rows[i].capsules.len()
            ));
        }
        let bodies = t.scene.bodies.len();
        if let Some(i) = t.rows.iter().position(|r| r.bodies.len() != bodies) {
            return Err(format!(
                "row {i}: {} body poses, scene names {bodies} bodies",
                t.rows[i].bodies.len()
            ));
        }
        if let Some(s) = t.scene.shapes.iter().find(|s| s.body >= bodies) {
            return Err(format!(
                "shape `{}` is on body {}, but the scene has {bodies} bodies",
                s.name, s.body
            ));
        }
        Ok(t)
    }

    /// The CSV header.
    pub fn csv_header() -> String {
        let mut cols = vec!["step".to_string(), "time_s".into()];
        cols.extend((1..=6).map(|i| format!("q{i}")));
        cols.push("gripper_opening_m".into());
        cols.extend(
            [
                "tcp_x", "tcp_y", "tcp_z", "tcp_qx", "tcp_qy", "tcp_qz", "tcp_qw",
            ]
            .map(String::from),
        );
        cols.extend(
            [
                "object_x",
                "object_y",
                "object_z",
                "object_qx",
                "object_qy",
                "object_qz",
                "object_qw",
            ]
            .map(String::from),
        );
        cols.extend((1..=6).map(|i| format!("action_j{i}")));
        cols.push("action_gripper".into());
        cols.push("reward".into());
        cols.extend(["pad_contact_left", "pad_contact_right", "phase"].map(String::from));
        cols.join(",")
    }

    /// The episode as CSV text.
    pub fn to_csv(&self) -> String {
        let mut out = Self::csv_header();
        out.push('\n');
        for r in &self.rows {
            let mut values = vec![r.step as f64, r.time_s];
            values.extend(r.joints);
            values.push(r.gripper_opening_m);
            values.extend(r.tcp_xyz.iter().chain(&r.tcp_quat_xyzw));
            values.extend(r.object_xyz.iter().chain(&r.object_quat_xyzw));
            values.extend(r.action);
            values.push(r.reward);
            values.extend(r.pad_contact.map(|c| f64::from(u8::from(c))));
            let mut line: Vec<String> = values.iter().map(|v| v.to_string()).collect();
            line.push(r.phase.clone().unwrap_or_default());
            out.push_str(&line.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes `<stem>.csv` and `<stem>.json` (compact) into `dir` (created if missing),
    /// atomically.
    pub fn save(&self, dir: &Path, stem: &str) -> std::io::Result<()> {
        std::fs::create_dir_all(dir)?;
        write_atomic(&dir.join(format!("{stem}.csv")), self.to_csv().as_bytes())?;
        let json = serde_json::to_vec(self).map_err(std::io::Error::other)?;
        write_atomic(&dir.join(format!("{stem}.json")), &json)
    }

    /// Writes `<stem>.json.gz` into `dir` (created if missing), atomically: the JSON with every
    /// number rounded to [`COMPACT_DECIMALS`] decimals, gzipped (about 20 kB for a 200-step
    /// episode, against 620 kB of JSON and CSV). Returns the file's name.
    pub fn save_compact(&self, dir: &Path, stem: &str) -> std::io::Result<String> {
        use std::io::Write;
        let mut value = serde_json::to_value(self).map_err(std::io::Error::other)?;
        round_numbers(&mut value, COMPACT_DECIMALS);
        let json = serde_json::to_vec(&value).map_err(std::io::Error::other)?;
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
        gz.write_all(&json)?;
        let name = format!("{stem}.json.gz");
        write_atomic(&dir.join(&name), &gz.finish()?)?;
        Ok(name)
    }

    /// Reads a trajectory written by [`Trajectory::save`] (`.json`) or
    /// [`Trajectory::save_compact`] (`.json.gz`, told by the gzip header), at most
    /// `max_bytes` of JSON, and checks it ([`Trajectory::from_json`]).
    pub fn from_bytes(bytes: &[u8], max_bytes: u64) -> Result<Self, String> {
        use std::io::Read;
        let text = if bytes.starts_with(&[0x1f, 0x8b]) {
            let mut text = String::new();
            flate2::read::GzDecoder::new(bytes)
                .take(max_bytes + 1)
                .read_to_string(&mut text)
                .map_err(|e| format!("not a gzipped fairgrasp trajectory: {e}"))?;
            if text.len() as u64 > max_bytes {
                return Err(format!("its JSON is over {max_bytes} bytes unpacked"));
            }
            text
        } else {
            String::from_utf8(bytes.to_vec())
                .map_err(|e| format!("not a fairgrasp trajectory JSON: {e}"))?
        };
        Self::from_json(&text)
    }
}

/// Decimals every number of a compact trajectory keeps ([`Trajectory::save_compact`]).
pub const COMPACT_DECIMALS: i32 = 5;

/// Rounds every non-integer number in `value` to `decimals` decimals.
fn round_numbers(value: &mut serde_json::Value, decimals: i32) {
    let scale = 10f64.powi(decimals);
    match value {
        serde_json::Value::Number(n) if n.is_f64() => {
            let x = n.as_f64().unwrap_or_default();
            if let Some(r) = serde_json::Number::from_f64((x * scale).round() / scale) {
                *n = r;
            }
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(|v| round_numbers(v, decimals)),
        serde_json::Value::Object(o) => o.values_mut().for_each(|v| round_numbers(v, decimals)),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn episode() -> Trajectory {
        let rows = (0..50)
            .map(|k| {
                let t = k as f64 / 12.0;
                TrajectoryRow {
                    step: k,
                    time_s: t,
                    joints: [0.1 * t.sin(), -1.3, -1.4, -1.9, 1.5, t],
                    gripper_opening_m: 0.085 - 0.000_123_456_789 * k as f64,
                    tcp_xyz: [0.3 + 0.001 * t, 0.0, 0.25],
                    tcp_quat_xyzw: [1.0, 0.0, 0.0, 0.0],
                    object_xyz: [0.35, 0.01, 0.025],
                    object_quat_xyzw: [0.0, 0.0, 0.0, 1.0],
                    action: [0.123_456_789; 7],
                    reward: -0.001_234_567,
                    capsules: vec![],
                    bodies: vec![],
                    pad_contact: [k > 20, k > 21],
                    events: vec![],
                    phase: Some("descend".into()),
                }
            })
            .collect();
        Trajectory {
            scene: TrajectoryScene::default(),
            rows,
            outcome: Some(Outcome::Success),
        }
    }

    #[test]
    fn a_compact_trajectory_reads_back_within_its_rounding_and_is_smaller() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-compact-{}", std::process::id()));
        let t = episode();
        let name = t.save_compact(&dir, "ep").unwrap();
        let bytes = std::fs::read(dir.join(&name)).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        let back = Trajectory::from_bytes(&bytes, 1 << 20).unwrap();
        let plain = serde_json::to_vec(&t).unwrap();
        assert!(
            bytes.len() * 4 < plain.len(),
            "{} vs {}",
            bytes.len(),
            plain.len()
        );
        assert_eq!(back.rows.len(), t.rows.len());
        assert_eq!(back.outcome, t.outcome);
        let half_quantum = 0.5 * 10f64.powi(-COMPACT_DECIMALS) + 1e-12;
        for (a, b) in t.rows.iter().zip(&back.rows) {
            assert_eq!(
                (a.step, &a.phase, a.pad_contact),
                (b.step, &b.phase, b.pad_contact)
            );
            for (x, y) in a
                .joints
                .iter()
                .chain(&a.action)
                .zip(b.joints.iter().chain(&b.action))
            {
                assert!((x - y).abs() <= half_quantum, "{x} vs {y}");
            }
            assert!((a.gripper_opening_m - b.gripper_opening_m).abs() <= half_quantum);
        }
    }

    #[test]
    fn a_gzipped_trajectory_larger_than_the_cap_is_refused_unpacked() {
        let dir = std::env::temp_dir().join(format!("fairgrasp-cap-{}", std::process::id()));
        let name = episode().save_compact(&dir, "ep").unwrap();
        let bytes = std::fs::read(dir.join(&name)).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        let err = Trajectory::from_bytes(&bytes, 1000).unwrap_err();
        assert!(err.contains("over 1000 bytes"), "{err}");
    }
}
