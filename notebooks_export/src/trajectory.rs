//! An episode trajectory as the env writes it (`episode_NNNN.json`): per-step joints, gripper,
//! TCP and object positions, and the capsules of arm and gripper, all in `base_link` [m].

use std::path::Path;

use serde::Deserialize;

use crate::error::{ReportError, read_text};

/// One recorded step (the fields the charts use).
#[derive(Clone, Debug, Deserialize)]
pub struct StepRecord {
    /// Simulated time [s].
    pub time_s: f64,
    /// Joint angles [rad].
    pub joints: [f64; 6],
    /// Distance between the pads [m].
    pub gripper_opening_m: f64,
    pub tcp_xyz: [f64; 3],
    pub object_xyz: [f64; 3],
    /// Object orientation as a quaternion `[x, y, z, w]`.
    #[serde(default = "identity_quat")]
    pub object_quat_xyzw: [f64; 4],
    /// `[ax, ay, az, bx, by, bz, radius]` per capsule, named in [`SceneRecord::capsule_names`].
    #[serde(default)]
    pub capsules: Vec<[f64; 7]>,
}

fn identity_quat() -> [f64; 4] {
    [0.0, 0.0, 0.0, 1.0]
}

/// Table and cube geometry in `base_link`.
#[derive(Clone, Debug, Default, Deserialize)]
pub struct SceneRecord {
    pub table_corners_xy: [[f64; 2]; 4],
    pub table_top_z: f64,
    pub cube_size: f64,
    pub capsule_names: Vec<String>,
}

/// A recorded episode.
#[derive(Clone, Debug, Deserialize)]
pub struct EpisodeTrajectory {
    #[serde(default)]
    pub scene: SceneRecord,
    pub rows: Vec<StepRecord>,
}

impl StepRecord {
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

impl EpisodeTrajectory {
    /// Reads a trajectory JSON file.
    pub fn load(path: &Path) -> Result<Self, ReportError> {
        let t: Self = serde_json::from_str(&read_text(path)?).map_err(|e| {
            ReportError::malformed(path, format!("not a fairgrasp trajectory JSON: {e}"))
        })?;
        if t.rows.is_empty() {
            return Err(ReportError::malformed(path, "trajectory has no rows"));
        }
        let n = t.scene.capsule_names.len();
        if let Some(i) = t.rows.iter().position(|r| r.capsules.len() != n) {
            return Err(ReportError::malformed(
                path,
                format!(
                    "row {i}: {} capsules, scene names {n}",
                    t.rows[i].capsules.len()
                ),
            ));
        }
        Ok(t)
    }
}
