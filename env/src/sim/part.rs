//! The named parts of the scene: what each collider belongs to (table, cube, arm links, palm,
//! finger struts, pads), for collision reports, contact forces and the exact shapes.

use fairgrasp_kinematics::ArmModel;
use rapier3d::prelude::ColliderHandle;

/// The table's name in collision reports ([`Part::name`]).
pub const TABLE_PART_NAME: &str = "table";

/// What a collider belongs to, for collision reports and finger contacts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    Table,
    /// The place task's fixture: the pocket's walls, bolted to the table.
    Fixture,
    Cube,
    /// Arm link by index: 0 = base_link … 6 = wrist3_link.
    Link(usize),
    Palm,
    /// Finger strut: 0 = left, 1 = right.
    Finger(usize),
    /// Finger pad: 0 = left, 1 = right.
    Pad(usize),
}

/// Every part of the robot, arm links first (base_link … wrist3_link), then the gripper.
pub const ROBOT_PARTS: [Part; 12] = [
    Part::Link(0),
    Part::Link(1),
    Part::Link(2),
    Part::Link(3),
    Part::Link(4),
    Part::Link(5),
    Part::Link(6),
    Part::Palm,
    Part::Finger(0),
    Part::Finger(1),
    Part::Pad(0),
    Part::Pad(1),
];

impl Part {
    /// The URDF link name (or "table", "cube").
    pub fn name(self, model: &ArmModel) -> &'static str {
        match self {
            Part::Table => TABLE_PART_NAME,
            Part::Fixture => "fixture",
            Part::Cube => "cube",
            Part::Link(i) => model.links[i],
            Part::Palm => "palm",
            Part::Finger(0) => "finger_left",
            Part::Finger(_) => "finger_right",
            Part::Pad(0) => "finger_left_pad",
            Part::Pad(_) => "finger_right_pad",
        }
    }

    /// Arm or gripper: the parts whose contacts can be collisions.
    pub fn is_robot(self) -> bool {
        !matches!(self, Part::Table | Part::Fixture | Part::Cube)
    }

    /// Is this part a body that never responds to forces in the servo arm's world: the links and
    /// the palm (kinematic, placed by FK), the table and the fixture (fixed)? Rapier does not
    /// compute contacts between two such parts ([`crate::sim::scene::build`]); the env checks the
    /// links' and palm's pairs with the table on the exact shapes instead
    /// ([`crate::sim::shapes::RobotShapes`]). The fixture's walls stand below anything but the
    /// fingers reach (which are dynamic, so rapier computes their contacts with it).
    pub fn never_moved_by_forces(self) -> bool {
        matches!(
            self,
            Part::Table | Part::Fixture | Part::Link(_) | Part::Palm
        )
    }
}

/// Which part each collider of the scene is: a table indexed by the handle's slot (the scene's
/// colliders are never removed, so the slots are few and dense). Looked up for the cube's and
/// the table's contact pairs after every physics substep (the protective stop) and for every
/// pair after every step, where hashing the handles cost 2 % of an episode.
#[derive(Clone, Debug, Default)]
pub struct ColliderParts {
    /// Slot → (handle, part).
    slots: Vec<Option<(ColliderHandle, Part)>>,
}

impl ColliderParts {
    /// Records that `handle` is `part`.
    pub fn insert(&mut self, handle: ColliderHandle, part: Part) {
        let slot = handle.into_raw_parts().0 as usize;
        if self.slots.len() <= slot {
            self.slots.resize(slot + 1, None);
        }
        self.slots[slot] = Some((handle, part));
    }

    /// The part `handle` is, if it is one of the scene's (same slot and generation).
    pub fn get(&self, handle: &ColliderHandle) -> Option<Part> {
        let slot = handle.into_raw_parts().0 as usize;
        match self.slots.get(slot) {
            Some(Some((h, part))) if h == handle => Some(*part),
            _ => None,
        }
    }

    /// Every collider and its part, in slot order.
    pub fn iter(&self) -> impl Iterator<Item = (ColliderHandle, Part)> + '_ {
        self.slots.iter().flatten().copied()
    }
}
