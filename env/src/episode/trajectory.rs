//! Recording an episode from the env into the one trajectory type
//! ([`fairgrasp_types::trajectory::Trajectory`]: written here, read by the report), saved as CSV
//! and JSON (atomically).
//!
//! Besides the joints, poses, action and reward, every row holds the pose of each rigid body of
//! the robot (the seven arm links, the palm on `tool0`, the two fingers) in `base_link`, and the
//! scene the collision shapes fixed to them — the simulation's own, from the same functions
//! that build the physics world ([`crate::sim::scene`]) — so a replay draws what was simulated.

use fairgrasp_kinematics::{ArmModel, world_to_base};
use fairgrasp_types::body::{BodyShape, Geometry, Pose7, WorldBox};
pub use fairgrasp_types::trajectory::{Trajectory, TrajectoryRow, TrajectoryScene};
use nalgebra::Isometry3;

use crate::env::{Action, Step, TaskEnv};
use crate::scenario::nudge::NudgeEvent;
use crate::sim::scene;
use crate::task::Failure;

/// Recording an episode from the env into a [`Trajectory`].
pub trait Recorder {
    /// Records the state right after a reset (`opening`: the gripper opening \[m\]); clears
    /// earlier rows.
    fn record_reset(&mut self, env: &TaskEnv, opening: f64);
    /// Records the state after a step; `phase` is the policy's phase when it chose the action
    /// ([`crate::episode::Policy::phase`]).
    fn record_step(&mut self, env: &TaskEnv, action: &Action, step: &Step, phase: Option<&str>);
}

impl Recorder for Trajectory {
    fn record_reset(&mut self, env: &TaskEnv, opening: f64) {
        self.rows.clear();
        self.outcome = None;
        push(self, env, [0.0; 7], 0.0, opening);
    }

    fn record_step(&mut self, env: &TaskEnv, action: &Action, step: &Step, phase: Option<&str>) {
        push(self, env, action.0, step.reward, step.obs.gripper_opening);
        let row = self.rows.len() - 1;
        let events = events_of(env, step, row);
        if let Some(last) = self.rows.last_mut() {
            last.phase = phase.map(String::from);
            last.events = events;
        }
        if let Some(record) = &step.info.episode {
            self.outcome = Some(record.outcome);
        }
    }
}

/// What happened in the step that led to row `row`: a collision, a protective stop, the cube
/// off the table, or pushed before this step's action.
fn events_of(env: &TaskEnv, step: &Step, row: usize) -> Vec<String> {
    let mut events = Vec::new();
    match &step.info.failure {
        Some(Failure::Collision(a, b)) => events.push(format!("collision: {a} – {b}")),
        Some(Failure::ProtectiveStop {
            robot_part,
            other_part,
            force_n,
        }) => events.push(format!(
            "protective stop: {robot_part} on {other_part}, {force_n:.0} N"
        )),
        Some(Failure::ObjectOffTable) => events.push("cube off the table".into()),
        None => {
            if let Some((a, b, depth)) = env.contacts().collision {
                let model = env.model();
                events.push(format!(
                    "collision: {} – {} ({:.1} mm)",
                    a.name(model),
                    b.name(model),
                    depth * 1e3
                ));
            }
        }
    }
    if let Some(NudgeEvent::Pushed { step, from, to, .. }) = env.nudge_event()
        && step + 1 == row
    {
        let d = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
        events.push(format!("cube pushed {:.1} cm", d * 100.0));
    }
    events
}

/// Appends the env's current state as a row (the scene with the first row).
fn push(t: &mut Trajectory, env: &TaskEnv, action: [f64; 7], reward: f64, opening: f64) {
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
        bodies: body_poses(env.model(), &env.joints(), env.finger_travel())
            .into_iter()
            .chain(env.fixture_in_base().map(|f| pose7(&f.iso)))
            .collect(),
        pad_contact: env.contacts().pad_contact,
        events: Vec::new(),
        phase: None,
    });
}

/// Names of the recorded bodies: the arm's links, the palm (its frame is `tool0`), the fingers.
fn body_names(model: &ArmModel) -> Vec<String> {
    model
        .links
        .iter()
        .map(|l| l.to_string())
        .chain(["palm", "finger_left", "finger_right"].map(String::from))
        .collect()
}

/// The pose of every body of [`body_names`] in `base_link` at joints `q` \[rad\] and finger
/// travels `travel` \[m\] (0 = open), placed as the simulation places them.
fn body_poses(model: &ArmModel, q: &[f64; 6], travel: [f64; 2]) -> Vec<Pose7> {
    let tool0 = model.fk_flange(q).iso;
    model
        .link_poses(q)
        .into_iter()
        .chain([tool0])
        .chain((0..2).map(|f| tool0 * scene::finger_in_tool0(model, f, travel[f])))
        .map(|iso| pose7(&iso))
        .collect()
}

fn pose7(iso: &Isometry3<f64>) -> Pose7 {
    let t = iso.translation.vector;
    let q = iso.rotation.coords; // x, y, z, w
    [t.x, t.y, t.z, q.x, q.y, q.z, q.w]
}

/// The collision shapes on the bodies of [`body_names`]: a capsule per link, the palm box on
/// `tool0`, a strut and a pad box on each finger.
fn body_shapes(model: &ArmModel) -> Vec<BodyShape> {
    let shape = |name: &str, body: usize, geometry: Geometry| BodyShape {
        name: name.to_string(),
        body,
        geometry,
    };
    let cuboid = |(half_extents, centre): ([f64; 3], [f64; 3])| Geometry::Box {
        centre,
        half_extents,
    };
    let mut shapes: Vec<BodyShape> = model
        .capsules
        .iter()
        .filter_map(|c| {
            let body = model.links.iter().position(|l| *l == c.link)?;
            let geometry = Geometry::Capsule {
                a: c.from,
                b: c.to,
                radius: c.radius,
            };
            Some(shape(c.link, body, geometry))
        })
        .collect();
    let palm = model.links.len();
    shapes.push(shape("palm", palm, cuboid(scene::palm_box(model))));
    for (f, side) in ["left", "right"].into_iter().enumerate() {
        let finger = palm + 1 + f;
        let strut = cuboid(scene::strut_box(model, f));
        shapes.push(shape(&format!("finger_{side}"), finger, strut));
        let pad = cuboid(scene::pad_box(model));
        shapes.push(shape(&format!("finger_{side}_pad"), finger, pad));
    }
    shapes
}

/// The table, cube, mount and robot geometry of `env`'s scene.
fn scene_of(env: &TaskEnv, capsule_names: Vec<String>) -> TrajectoryScene {
    let config = env.config();
    let scene = &config.scene;
    let base = env.base_in_world();
    let [bx, by, _] = base.xyz();
    let [hx, hy] = scene.table_size.map(|s| 0.5 * s);
    let corner = |sx: f64, sy: f64| {
        let p = world_to_base(base, [bx + sx * hx, by + sy * hy, scene.table_height]);
        [p[0], p[1]]
    };
    let (half_extents, centre) = scene::table_box(config, [bx, by]);
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
        base_in_world: pose7(&base.iso),
        table_in_world: Some(WorldBox {
            centre,
            half_extents,
        }),
        bodies: body_names(env.model())
            .into_iter()
            .chain(env.fixture_in_base().map(|_| "fixture".to_string()))
            .collect(),
        shapes: body_shapes(env.model())
            .into_iter()
            .chain(fixture_shapes(env))
            .collect(),
    }
}

/// The task's fixture's boxes (the place task's walls, the stack task's second cube), on the
/// body after the robot's (none for a task without a fixture).
fn fixture_shapes(env: &TaskEnv) -> Vec<BodyShape> {
    if env.fixture_in_base().is_none() {
        return Vec::new();
    }
    let config = env.config();
    let body = body_names(env.model()).len();
    let spec = config.task.kind.spec();
    (spec.fixture_boxes)(&config.task, config.scene.cube_size)
        .into_iter()
        .enumerate()
        .map(|(k, (half_extents, centre))| BodyShape {
            name: format!("{}_{k}", spec.fixture_part),
            body,
            geometry: Geometry::Box {
                centre,
                half_extents,
            },
        })
        .collect()
}
