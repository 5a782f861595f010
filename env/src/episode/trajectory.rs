//! Episode recording: per step joints, TCP pose, object pose, action and reward, exported as
//! CSV and JSON (written atomically: a temporary file, then a rename).

use std::path::Path;

use serde::Serialize;

use fairgrasp_kinematics::world_to_base;

use crate::env::{Action, GraspEnv, Step};

/// One recorded step; poses in `base_link`, quaternions `[x, y, z, w]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TrajectoryRow {
    /// Step index (0 = the state after reset).
    pub step: usize,
    /// Simulated time [s].
    pub time_s: f64,
    pub joints: [f64; 6],
    pub gripper_opening_m: f64,
    pub tcp_xyz: [f64; 3],
    pub tcp_quat_xyzw: [f64; 4],
    pub object_xyz: [f64; 3],
    pub object_quat_xyzw: [f64; 4],
    /// The action that led here (zeros for step 0).
    pub action: [f64; 7],
    pub reward: f64,
    /// The arm's and gripper's collision capsules at this step, in the order of
    /// [`TrajectoryScene::capsule_names`]: `[ax, ay, az, bx, by, bz, radius]` in `base_link` [m]
    /// (JSON only; for replays).
    pub capsules: Vec<[f64; 7]>,
}

/// What a replay needs besides the rows: the table and cube in `base_link` [m].
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
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
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Trajectory {
    pub scene: TrajectoryScene,
    pub rows: Vec<TrajectoryRow>,
}

impl Trajectory {
    fn push(&mut self, env: &GraspEnv, action: [f64; 7], reward: f64, opening: f64) {
        let step = self.rows.len();
        let cfg = &env.config().physics;
        let (tcp, object) = (env.tcp_in_base(), env.object_in_base());
        let placed = env
            .model()
            .placed_capsules_with_opening(&env.joints(), opening);
        if step == 0 {
            self.scene = scene_of(env, placed.iter().map(|c| c.name.to_string()).collect());
        }
        self.rows.push(TrajectoryRow {
            step,
            time_s: step as f64 * cfg.dt * cfg.substeps as f64,
            joints: env.joints(),
            gripper_opening_m: opening,
            tcp_xyz: tcp.xyz(),
            tcp_quat_xyzw: tcp.quat_xyzw(),
            object_xyz: object.xyz(),
            object_quat_xyzw: object.quat_xyzw(),
            action,
            reward,
            capsules: placed
                .iter()
                .map(|c| [c.a[0], c.a[1], c.a[2], c.b[0], c.b[1], c.b[2], c.radius])
                .collect(),
        });
    }

    /// Records the state right after a reset.
    pub fn record_reset(&mut self, env: &GraspEnv, opening: f64) {
        self.rows.clear();
        self.push(env, [0.0; 7], 0.0, opening);
    }

    /// Records the state after a step.
    pub fn record_step(&mut self, env: &GraspEnv, action: &Action, step: &Step) {
        self.push(env, action.0, step.reward, step.obs.gripper_opening);
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

/// The table and cube of `env`'s scene in `base_link`.
fn scene_of(env: &GraspEnv, capsule_names: Vec<String>) -> TrajectoryScene {
    let scene = &env.config().scene;
    let base = env.base_in_world();
    let [bx, by, _] = base.xyz();
    let [hx, hy] = scene.table_size.map(|s| 0.5 * s);
    let corner = |sx: f64, sy: f64| {
        let p = world_to_base(base, [bx + sx * hx, by + sy * hy, scene.table_height]);
        [p[0], p[1]]
    };
    TrajectoryScene {
        table_corners_xy: [
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
            corner(1.0, 1.0),
            corner(-1.0, 1.0),
        ],
        table_top_z: world_to_base(base, [bx, by, scene.table_height])[2],
        cube_size: scene.cube_size,
        capsule_names,
    }
}

/// The one atomic file write, kept at this path for the crates that import it from here.
pub use fairgrasp_types::write_atomic;
