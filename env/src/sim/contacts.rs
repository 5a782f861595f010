//! Reading the narrow phase: collisions (with the pair named) and finger–cube contacts.

use rapier3d::prelude::*;

pub use crate::sensor::wrench::Wrench;
pub use crate::sim::collision_filter::CollisionFilter;
use crate::sim::part::{ColliderParts, Part};
use crate::sim::scene::SceneHandles;

/// A contact counts as touching below this signed distance \[m\] (negative = penetrating).
const TOUCH_DISTANCE: f32 = 0.0;
/// A pad counts as touching the cube within this distance \[m\].
const PAD_CONTACT_DISTANCE: f32 = 0.001;

/// What the contacts say after a step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactReport {
    /// The first colliding pair found, deepest first: (part, part, penetration \[m\]).
    pub collision: Option<(Part, Part, f64)>,
    /// Left and right pad touching the cube.
    pub pad_contact: [bool; 2],
    /// Deepest penetration of a pad into the cube \[m\] (0 when apart).
    pub pad_penetration: f64,
}

/// How a touching pair is judged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairKind {
    /// Counts as a collision (ends the episode by default).
    Collision,
    /// A contact with the object: resting on the table, or held by the pads.
    Object,
    /// A robot pair fairgrasp never counts (adjacent links, the base on its table, gripper parts).
    Ignored,
    /// Neither part belongs to the robot.
    Scene,
}

/// One touching pair: its parts, signed distance \[m\] (negative = penetrating) and kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TouchingPair {
    pub a: Part,
    pub b: Part,
    pub distance: f64,
    pub kind: PairKind,
}

/// The deepest contact of every narrow-phase pair between two scene parts: `(a, b, signed
/// distance \[m\])`.
fn part_contacts<'a>(
    world: &'a PhysicsWorld,
    handles: &'a SceneHandles,
) -> impl Iterator<Item = (Part, Part, f32)> + 'a {
    world.narrow_phase.contact_pairs().filter_map(|pair| {
        let a = handles.parts.get(&pair.collider1)?;
        let b = handles.parts.get(&pair.collider2)?;
        let (_, contact) = pair.find_deepest_contact()?;
        Some((a, b, contact.dist))
    })
}

/// Every pair of the narrow phase closer than `TOUCH_DISTANCE`, deepest first, judged by
/// `filter`. Pairs excluded by collision groups, and pairs of two bodies forces never move (the
/// servo arm's links and palm, the table), are never computed and do not appear here
/// (`TaskEnv::touching_pairs` adds the latter from the exact shapes).
pub fn touching_pairs(
    world: &PhysicsWorld,
    handles: &SceneHandles,
    filter: &CollisionFilter,
) -> Vec<TouchingPair> {
    let mut out = Vec::new();
    for (a, b, dist) in part_contacts(world, handles) {
        if dist > TOUCH_DISTANCE {
            continue;
        }
        let kind = if filter.is_collision(a, b) {
            PairKind::Collision
        } else if a == Part::Cube || b == Part::Cube {
            PairKind::Object
        } else if a.is_robot() || b.is_robot() {
            PairKind::Ignored
        } else {
            PairKind::Scene
        };
        out.push(TouchingPair {
            a,
            b,
            distance: f64::from(dist),
            kind,
        });
    }
    out.sort_by(|x, y| x.distance.total_cmp(&y.distance));
    out
}

/// Scans every contact pair of the narrow phase.
pub fn analyze(
    world: &PhysicsWorld,
    handles: &SceneHandles,
    filter: &CollisionFilter,
) -> ContactReport {
    let mut report = ContactReport::default();
    for (a, b, dist) in part_contacts(world, handles) {
        for f in 0..2 {
            if (a, b) == (Part::Pad(f), Part::Cube) || (b, a) == (Part::Pad(f), Part::Cube) {
                report.pad_contact[f] |= dist < PAD_CONTACT_DISTANCE;
                report.pad_penetration = report.pad_penetration.max(-dist as f64);
            }
        }
        if dist < TOUCH_DISTANCE && filter.is_collision(a, b) {
            let depth = -dist as f64;
            if report.collision.is_none_or(|(_, _, d)| depth > d) {
                report.collision = Some((a, b, depth));
            }
        }
    }
    report
}

/// The strongest solver contact between a robot part and the cube or the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotContactForce {
    /// The robot's part (arm link, palm, finger strut or pad).
    pub robot: Part,
    /// What it pushes on: [`Part::Cube`] or [`Part::Table`].
    pub other: Part,
    /// Magnitude of the pair's net contact force \[N\] (solver impulse over the physics step).
    pub force: f64,
}

/// The strongest robot–cube or robot–table contact force of the last physics step of `dt` \[s\]:
/// each pair's net impulse \[N·s\] (normal impulses summed over its manifolds) divided by `dt`.
///
/// Only the pairs of `cube` and `table` are visited (through the narrow phase's per-collider
/// adjacency, no allocation). A kinematic link or palm against the fixed table is not in the
/// narrow phase at all (no force could act between them); such a touch is a collision, found on
/// the exact shapes at the end of the step.
pub fn strongest_robot_contact(
    world: &PhysicsWorld,
    parts: &ColliderParts,
    cube: ColliderHandle,
    table: ColliderHandle,
    dt: f64,
) -> Option<RobotContactForce> {
    let mut strongest: Option<RobotContactForce> = None;
    let pairs = world
        .narrow_phase
        .contact_pairs_with(cube)
        .chain(world.narrow_phase.contact_pairs_with(table));
    for pair in pairs {
        let (Some(a), Some(b)) = (parts.get(&pair.collider1), parts.get(&pair.collider2)) else {
            continue;
        };
        let (robot, other) = match (a.is_robot(), b.is_robot()) {
            (true, false) => (a, b),
            (false, true) => (b, a),
            _ => continue,
        };
        let force = f64::from(pair.total_impulse().length()) / dt;
        if strongest.is_none_or(|s| force > s.force) {
            strongest = Some(RobotContactForce {
                robot,
                other,
                force,
            });
        }
    }
    strongest
}

/// What a six-axis wrist sensor between the flange and the gripper reads, tared for the held
/// load: the wrench the table and the fixture apply, over the last physics step, on the gripper
/// (palm, fingers, pads) and, when `holding`, on the cube, in `world`, the torque taken about
/// `about` (the sensor's origin, `world` \[m\]).
///
/// Why this is the tared reading: quasi-statically, the sensor carries the gripper's and the held
/// cube's weight plus every external push on them; taring (FAIRINO's load identification) takes
/// the weight away, leaving the external contacts. Inertial loads are left out (the cube moves at
/// centimetres per second when it touches).
///
/// Each contact point contributes its normal impulse along its manifold's normal (which points
/// from the pair's first collider to its second: `n·λ` is what the second receives) at the
/// point; with `step.friction`, each manifold its friction impulse at the mean of its points
/// (rapier's simplified friction model solves one friction constraint per manifold, at its
/// friction centre; its twist, a torque about the normal, is left out, so the torque about the
/// contact's normal is not read in full). The normal impulses are the step's totals over the
/// solver's substeps; rapier keeps only the last substep's friction impulse, so it is scaled by
/// the manifold's ratio of total to last-substep normal impulse (`solver_iterations` when that
/// is undefined). Impulses divided by `dt` \[s\] are forces.
pub fn wrist_wrench(
    world: &PhysicsWorld,
    parts: &ColliderParts,
    step: WrenchStep,
    holding: bool,
    about: Vec3,
) -> Wrench {
    let fixed = |p: Part| matches!(p, Part::Table | Part::Fixture);
    let carried = |p: Part| {
        matches!(p, Part::Palm | Part::Finger(_) | Part::Pad(_)) || (holding && p == Part::Cube)
    };
    let mut wrench = Wrench::default();
    for pair in world.narrow_phase.contact_pairs() {
        let (Some(a), Some(b)) = (parts.get(&pair.collider1), parts.get(&pair.collider2)) else {
            continue;
        };
        // +1: the carried part is the pair's second collider (it receives +n·λ).
        let sign = if fixed(a) && carried(b) {
            1.0
        } else if fixed(b) && carried(a) {
            -1.0
        } else {
            continue;
        };
        let Some(first) = world.colliders.get(pair.collider1) else {
            continue;
        };
        let first_pose = *first.position();
        for manifold in pair.solver_manifolds() {
            add_manifold(&mut wrench, manifold, &first_pose, step, sign, about);
        }
    }
    wrench
}

/// The time a step's impulses were gathered over, and how many solver substeps it had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WrenchStep {
    /// The physics step \[s\].
    pub dt: f64,
    /// The solver's substeps per physics step (`num_solver_iterations`).
    pub solver_iterations: usize,
    /// Read the contacts' friction too (`[sensor.wrench] friction`), not their normal impulses
    /// only.
    pub friction: bool,
}

/// Adds one manifold's contacts, as received by the carried side (`sign`), to `wrench`.
fn add_manifold(
    wrench: &mut Wrench,
    manifold: &ContactManifold,
    first_pose: &Pose,
    step: WrenchStep,
    sign: f64,
    about: Vec3,
) {
    let normal = manifold.data.normal;
    let (mut total, mut last) = (0.0f64, 0.0f64);
    let mut centre = Vec3::ZERO;
    let mut count = 0.0f32;
    for point in &manifold.points {
        let at = first_pose * point.local_p1;
        let impulse = f64::from(point.data.impulse);
        total += impulse;
        last += f64::from(point.data.warmstart_impulse);
        add_force(
            wrench,
            normal * point.data.impulse,
            at,
            sign,
            step.dt,
            about,
        );
        centre += at;
        count += 1.0;
    }
    let Some(point) = manifold.points.first().filter(|_| step.friction) else {
        return;
    };
    // The friction impulse rapier applies to the first collider (`warmstart_tangent_world`):
    // the second receives its opposite.
    let substeps = if last > 1e-12 {
        total / last
    } else {
        step.solver_iterations as f64
    };
    let friction = -point.data.warmstart_tangent_world * substeps as f32;
    add_force(wrench, friction, centre / count, sign, step.dt, about);
}

/// Adds the impulse `impulse` \[N·s\] received by the pair's second collider at `at` (both
/// `world`), as the carried side receives it (`sign`), as a force and its torque about `about`.
fn add_force(wrench: &mut Wrench, impulse: Vec3, at: Vec3, sign: f64, dt: f64, about: Vec3) {
    let f = [impulse.x, impulse.y, impulse.z].map(|v| f64::from(v) * sign / dt);
    let r = [at.x - about.x, at.y - about.y, at.z - about.z].map(f64::from);
    let torque = [
        r[1] * f[2] - r[2] * f[1],
        r[2] * f[0] - r[0] * f[2],
        r[0] * f[1] - r[1] * f[0],
    ];
    for i in 0..3 {
        wrench.force[i] += f[i];
        wrench.torque[i] += torque[i];
    }
}
