//! One recorded episode, written by the env and read by the report (one type, one schema):
//! per step the joints, gripper, TCP and object poses, action, reward and the arm's capsules,
//! all in `base_link` [m], quaternions `[x, y, z, w]`; saved as CSV and JSON.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::fs::write_atomic;

fn identity_quat() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

/// One recorded step; poses in `base_link`, quaternions `[x, y, z, w]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrajectoryRow {
    /// Step index (0 = the state after reset).
    #[serde(default)]
    pub step: usize,
    /// Simulated time [s].
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
    /// [`TrajectoryScene::capsule_names`]: `[ax, ay, az, bx, by, bz, radius]` in `base_link` [m]
    /// (JSON only; for replays).
    #[serde(default)]
    pub capsules: Vec<[f64; 7]>,
}

/// What a replay needs besides the rows: the table and cube in `base_link` [m].
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
}

/// A recorded episode.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    #[serde(default)]
    pub scene: TrajectoryScene,
    pub rows: Vec<TrajectoryRow>,
}

impl TrajectoryRow {
    /// The cube's 8 corners in `base_link` for edge length `size` [m].
    pub fn cube_corners(&self, size: f64) -> [[f64; 3]; 8] {
        let [x, y, z, w] = self.object_quat_xyzw;
        let rotate = |v: [f64; 3]| {
            // v + 2w(q×v) + 2q×(q×v), q = (x, y, z)
            let q = [x, y, z];
            let cross = |a: [f64; 3], b: [f64; 3]| {
                [
                    a[1] * b[2] - a[2] * b[1],
                    a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0],
                ]
            };
            let t = cross(q, v).map(|c| 2.0 * c);
            let u = cross(q, t);
            [0, 1, 2].map(|i| v[i] + w * t[i] + u[i])
        };
        let h = 0.5 * size;
        let mut out = [[0.0; 3]; 8];
        for (i, corner) in out.iter_mut().enumerate() {
            let local = [
                if i & 1 == 0 { -h } else { h },
                if i & 2 == 0 { -h } else { h },
                if i & 4 == 0 { -h } else { h },
            ];
            let r = rotate(local);
            *corner = [0, 1, 2].map(|k| self.object_xyz[k] + r[k]);
        }
        out
    }
}

impl Trajectory {
    /// Parses a trajectory's JSON text and checks it: at least one row, and every row with the
    /// scene's number of capsules.
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
            let line: Vec<String> = values.iter().map(|v| v.to_string()).collect();
            out.push_str(&line.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes `<stem>.csv` and `<stem>.json` into `dir` (created if missing), atomically.
    pub fn save(&self, dir: &Path, stem: &str) -> std::io::Result<()> {
        std::fs::create_dir_all(dir)?;
        write_atomic(&dir.join(format!("{stem}.csv")), self.to_csv().as_bytes())?;
        let json = serde_json::to_vec_pretty(self).map_err(std::io::Error::other)?;
        write_atomic(&dir.join(format!("{stem}.json")), &json)
    }
}
