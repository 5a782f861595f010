//! Recording an episode from the env into the one trajectory type
//! ([`fairgrasp_types::trajectory::Trajectory`]: written here, read by the report), saved as CSV
//! and JSON (atomically).

use fairgrasp_kinematics::world_to_base;
pub use fairgrasp_types::trajectory::{Trajectory, TrajectoryRow, TrajectoryScene};

use crate::env::{Action, GraspEnv, Step};

/// Recording an episode from the env into a [`Trajectory`].
pub trait Recorder {
    /// Records the state right after a reset (`opening`: the gripper opening [m]); clears
    /// earlier rows.
    fn record_reset(&mut self, env: &GraspEnv, opening: f64);
    /// Records the state after a step.
    fn record_step(&mut self, env: &GraspEnv, action: &Action, step: &Step);
}

impl Recorder for Trajectory {
    fn record_reset(&mut self, env: &GraspEnv, opening: f64) {
        self.rows.clear();
        push(self, env, [0.0; 7], 0.0, opening);
    }

    fn record_step(&mut self, env: &GraspEnv, action: &Action, step: &Step) {
        push(self, env, action.0, step.reward, step.obs.gripper_opening);
    }
}

/// Appends the env's current state as a row (the scene with the first row).
fn push(t: &mut Trajectory, env: &GraspEnv, action: [f64; 7], reward: f64, opening: f64) {
    let step = t.rows.len();
    let cfg = &env.config().physics;
    let (tcp, object) = (env.tcp_in_base(), env.object_in_base());
    let placed = env
        .model()
        .placed_capsules_with_opening(&env.joints(), opening);
    if step == 0 {
        t.scene = scene_of(env, placed.iter().map(|c| c.name.to_string()).collect());
    }
    t.rows.push(TrajectoryRow {
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
