//! Reading the narrow phase: collisions (with the pair named) and finger–cube contacts.

use std::collections::{HashMap, HashSet};

use fairgrasp_kinematics::ArmModel;
use rapier3d::prelude::*;

use crate::scene::{Part, ROBOT_PARTS, SceneHandles};

/// A contact counts as touching below this signed distance [m] (negative = penetrating).
const TOUCH_DISTANCE: f32 = 0.0;
/// A pad counts as touching the cube within this distance [m].
const PAD_CONTACT_DISTANCE: f32 = 0.001;

/// Pairs of robot parts whose contacts are not collisions.
#[derive(Clone, Debug)]
pub struct CollisionFilter {
    ignored: HashSet<(Part, Part)>,
}

/// The pair in a fixed order, so that (a, b) and (b, a) are one key.
fn ordered(a: Part, b: Part) -> (Part, Part) {
    if a <= b { (a, b) } else { (b, a) }
}

impl CollisionFilter {
    /// Adjacent links, the model's ignored pairs, the base on its table, and the gripper's own
    /// parts (palm, struts and pads touch each other by construction).
    pub fn new(model: &ArmModel) -> Self {
        let mut ignored = HashSet::new();
        for i in 0..6 {
            ignored.insert(ordered(Part::Link(i), Part::Link(i + 1)));
        }
        let index = |name: &str| model.links.iter().position(|l| *l == name);
        for (a, b) in &model.ignored_collision_pairs {
            if let (Some(a), Some(b)) = (index(a), index(b)) {
                ignored.insert(ordered(Part::Link(a), Part::Link(b)));
            }
        }
        ignored.insert(ordered(Part::Link(0), Part::Table));
        // wrist3_link and the gripper's parts.
        let gripper = &ROBOT_PARTS[6..12];
        for (i, a) in gripper.iter().enumerate() {
            for b in &gripper[i + 1..] {
                ignored.insert(ordered(*a, *b));
            }
        }
        Self { ignored }
    }

    /// Is the pair `a`, `b` one whose contacts never matter?
    pub fn ignores(&self, a: Part, b: Part) -> bool {
        self.ignored.contains(&ordered(a, b))
    }

    /// Is a contact between `a` and `b` a collision?
    pub fn is_collision(&self, a: Part, b: Part) -> bool {
        let robot_involved = a.is_robot() || b.is_robot();
        let cube_involved = a == Part::Cube || b == Part::Cube;
        robot_involved && !cube_involved && !self.ignored.contains(&ordered(a, b))
    }
}

/// What the contacts say after a step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactReport {
    /// The first colliding pair found, deepest first: (part, part, penetration [m]).
    pub collision: Option<(Part, Part, f64)>,
    /// Left and right pad touching the cube.
    pub pad_contact: [bool; 2],
    /// Deepest penetration of a pad into the cube [m] (0 when apart).
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

/// One touching pair: its parts, signed distance [m] (negative = penetrating) and kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TouchingPair {
    pub a: Part,
    pub b: Part,
    pub distance: f64,
    pub kind: PairKind,
}

/// The deepest contact of every narrow-phase pair between two scene parts: `(a, b, signed
/// distance [m])`.
fn part_contacts<'a>(
    world: &'a PhysicsWorld,
    handles: &'a SceneHandles,
) -> impl Iterator<Item = (Part, Part, f32)> + 'a {
    world.narrow_phase.contact_pairs().filter_map(|pair| {
        let a = *handles.parts.get(&pair.collider1)?;
        let b = *handles.parts.get(&pair.collider2)?;
        let (_, contact) = pair.find_deepest_contact()?;
        Some((a, b, contact.dist))
    })
}

/// Every pair of the narrow phase closer than [`TOUCH_DISTANCE`], deepest first, judged by
/// `filter`. Pairs excluded by collision groups are never computed and do not appear.
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

/// The group bit of each part, so that ignored pairs are never even computed.
fn group_bit(part: Part) -> u32 {
    match part {
        Part::Link(i) => i as u32,
        Part::Palm => 7,
        Part::Finger(f) | Part::Pad(f) => 8 + f as u32,
        Part::Table => 10,
        Part::Cube => 11,
    }
}

/// Collision groups that skip the pairs [`CollisionFilter`] ignores (neighbouring links that
/// always overlap, the gripper's own parts, the base on its table): they cost narrow-phase time
/// every physics step and are never reported.
pub fn set_collision_groups(
    world: &mut PhysicsWorld,
    parts: &HashMap<ColliderHandle, Part>,
    model: &ArmModel,
) {
    let filter = CollisionFilter::new(model);
    for (handle, part) in parts {
        let mut allowed = 0u32;
        for other in ROBOT_PARTS.iter().chain(&[Part::Table, Part::Cube]) {
            if !filter.ignores(*part, *other) {
                allowed |= 1 << group_bit(*other);
            }
        }
        if let Some(c) = world.colliders.get_mut(*handle) {
            let groups = InteractionGroups::new(
                Group::from_bits_truncate(1 << group_bit(*part)),
                Group::from_bits_truncate(allowed),
                InteractionTestMode::And,
            );
            c.set_collision_groups(groups);
        }
    }
}

/// The strongest solver contact between a robot part and the cube or the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobotContactForce {
    /// The robot's part (arm link, palm, finger strut or pad).
    pub robot: Part,
    /// What it pushes on: [`Part::Cube`] or [`Part::Table`].
    pub other: Part,
    /// Magnitude of the pair's net contact force [N] (solver impulse over the physics step).
    pub force: f64,
}

/// The strongest robot–cube or robot–table contact force of the last physics step of `dt` [s]:
/// each pair's net impulse [N·s] (normal impulses summed over its manifolds) divided by `dt`.
///
/// Only the pairs of `cube` and `table` are visited (through the narrow phase's per-collider
/// adjacency, no allocation). A kinematic link against the fixed table has no solver contact,
/// hence no impulse; such a touch is a collision ([`CollisionFilter::is_collision`]) anyway.
pub fn strongest_robot_contact(
    world: &PhysicsWorld,
    parts: &HashMap<ColliderHandle, Part>,
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
        let (Some(&a), Some(&b)) = (parts.get(&pair.collider1), parts.get(&pair.collider2)) else {
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
