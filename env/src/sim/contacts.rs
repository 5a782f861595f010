//! Reading the narrow phase: collisions (with the pair named) and finger–cube contacts.

use rapier3d::prelude::*;

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

/// The force \[N, world\] the table and the fixture push with, over the last physics step of `dt`
/// \[s\], on the gripper (palm, fingers, pads) and, when `holding`, on the cube: what a wrist
/// force/torque sensor between the flange and the gripper reads once the held load's weight is
/// tared (a real FR3 cell reads it from FAIRINO's F/T option, or estimates it from the joint
/// torques: docs/place.md). Each pair's net contact impulse (normal impulses along its
/// manifolds' normals, which point from its first collider to its second: the impulse the
/// second receives) divided by `dt`.
pub fn wrist_load(world: &PhysicsWorld, parts: &ColliderParts, dt: f64, holding: bool) -> [f64; 3] {
    let fixed = |p: Part| matches!(p, Part::Table | Part::Fixture);
    let carried = |p: Part| {
        matches!(p, Part::Palm | Part::Finger(_) | Part::Pad(_)) || (holding && p == Part::Cube)
    };
    let mut force = [0.0; 3];
    for pair in world.narrow_phase.contact_pairs() {
        let (Some(a), Some(b)) = (parts.get(&pair.collider1), parts.get(&pair.collider2)) else {
            continue;
        };
        let sign = if fixed(a) && carried(b) {
            1.0
        } else if fixed(b) && carried(a) {
            -1.0
        } else {
            continue;
        };
        let impulse = pair.total_impulse();
        for (f, i) in force.iter_mut().zip([impulse.x, impulse.y, impulse.z]) {
            *f += sign * f64::from(i) / dt;
        }
    }
    force
}
