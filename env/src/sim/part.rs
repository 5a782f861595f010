//! The named parts of the scene: what each collider belongs to (table, cube, arm links, palm,
//! finger struts, pads), for collision reports, contact forces and the exact shapes.

use fairgrasp_kinematics::ArmModel;

/// What a collider belongs to, for collision reports and finger contacts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    Table,
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
            Part::Table => "table",
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
        !matches!(self, Part::Table | Part::Cube)
    }
}
