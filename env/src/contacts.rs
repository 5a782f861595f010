//! Reading the narrow phase: collisions (with the pair named) and finger–cube contacts.

use std::collections::HashSet;

use fairgrasp_kinematics::ArmModel;
use rapier3d::prelude::*;

use crate::scene::{Part, SceneHandles};

/// A contact counts as touching below this signed distance [m] (negative = penetrating).
const TOUCH_DISTANCE: f32 = 0.0;
/// A pad counts as touching the cube within this distance [m].
const PAD_CONTACT_DISTANCE: f32 = 0.001;

/// Pairs of robot parts whose contacts are not collisions.
#[derive(Clone, Debug)]
pub struct CollisionFilter {
    ignored: HashSet<(Part, Part)>,
}

fn ordered(a: Part, b: Part) -> (Part, Part) {
    let key = |p: Part| format!("{p:?}");
    if key(a) <= key(b) { (a, b) } else { (b, a) }
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
        let gripper = [
            Part::Link(6),
            Part::Palm,
            Part::Finger(0),
            Part::Finger(1),
            Part::Pad(0),
            Part::Pad(1),
        ];
        for (i, a) in gripper.iter().enumerate() {
            for b in &gripper[i + 1..] {
                ignored.insert(ordered(*a, *b));
            }
        }
        Self { ignored }
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

/// Scans every contact pair of the narrow phase.
pub fn analyze(
    world: &PhysicsWorld,
    handles: &SceneHandles,
    filter: &CollisionFilter,
) -> ContactReport {
    let mut report = ContactReport::default();
    for pair in world.narrow_phase.contact_pairs() {
        let (Some(&a), Some(&b)) = (
            handles.parts.get(&pair.collider1),
            handles.parts.get(&pair.collider2),
        ) else {
            continue;
        };
        let Some((_, contact)) = pair.find_deepest_contact() else {
            continue;
        };
        let dist = contact.dist;
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
