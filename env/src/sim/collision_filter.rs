//! Which contacts matter: the robot pairs that are never collisions (the arm model's one rule,
//! plus the base on its table), and rapier collision groups that skip them entirely.

use std::collections::HashSet;

use fairgrasp_kinematics::ArmModel;
use rapier3d::prelude::*;

use crate::sim::part::{ColliderParts, Part, ROBOT_PARTS};

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
    /// The robot pairs the arm model never checks ([`ArmModel::collision_ignored`]: adjacent
    /// links, the model's ignored pairs, the gripper's own parts), and the base on its table.
    pub fn new(model: &ArmModel) -> Self {
        let mut ignored = HashSet::new();
        for (i, a) in ROBOT_PARTS.iter().enumerate() {
            for b in &ROBOT_PARTS[i + 1..] {
                if model.collision_ignored(a.name(model), b.name(model)) {
                    ignored.insert(ordered(*a, *b));
                }
            }
        }
        ignored.insert(ordered(Part::Link(0), Part::Table));
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

/// The group bit of each part, so that ignored pairs are never even computed.
fn group_bit(part: Part) -> u32 {
    match part {
        Part::Link(i) => i as u32,
        Part::Palm => 7,
        Part::Finger(f) | Part::Pad(f) => 8 + f as u32,
        Part::Table => 10,
        Part::Cube => 11,
        Part::Fixture => 12,
    }
}

/// Collision groups that skip the pairs [`CollisionFilter`] ignores (neighbouring links that
/// always overlap, the gripper's own parts, the base on its table): they cost narrow-phase time
/// every physics step and are never reported.
pub fn set_collision_groups(world: &mut PhysicsWorld, parts: &ColliderParts, model: &ArmModel) {
    let filter = CollisionFilter::new(model);
    for (handle, part) in parts.iter() {
        let mut allowed = 0u32;
        for other in ROBOT_PARTS
            .iter()
            .chain(&[Part::Table, Part::Fixture, Part::Cube])
        {
            if !filter.ignores(part, *other) {
                allowed |= 1 << group_bit(*other);
            }
        }
        if let Some(c) = world.colliders.get_mut(handle) {
            let groups = InteractionGroups::new(
                Group::from_bits_truncate(1 << group_bit(part)),
                Group::from_bits_truncate(allowed),
                InteractionTestMode::And,
            );
            c.set_collision_groups(groups);
        }
    }
}
