//! FAIRINO's published numbers for the FR3 and FR5, in one place.
//!
//! Source: `docs/FR3.md` (FAIRINO's manual, DH sheet and ROS description, checked numerically;
//! the page says which numbers fairgrasp added itself). `assets/fr3.urdf` is written from the same numbers and a test checks
//! that the two agree.

use std::f64::consts::FRAC_PI_2;

use crate::model::{ArmKind, ArmModel, DhRow, GripperSpec, JointSpec, LinkCapsule, LinkInertial};
use crate::pose::Pose;

/// URDF link names of both arms, base to wrist.
pub const LINK_NAMES: [&str; 7] = [
    "base_link",
    "shoulder_link",
    "upperarm_link",
    "forearm_link",
    "wrist1_link",
    "wrist2_link",
    "wrist3_link",
];

/// FAIRINO's published check of the FR3 at zero joints (docs/FR3.md, "Checks"): the flange
/// (`tool0`) position in `base_link` \[m\]. The DH table below must reproduce it
/// (`kinematics/tests/fk.rs`), and `fairgrasp frames` prints the difference.
pub const FR3_ZERO_FLANGE_XYZ: [f64; 3] = [-0.520, -0.202, 0.038];

/// The same check's flange orientation: the rows of `R_base_tool0` at zero joints.
pub const FR3_ZERO_FLANGE_ROTATION: [[f64; 3]; 3] =
    [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];

const DEG: f64 = std::f64::consts::PI / 180.0;

/// Manual soft limits and velocity limits (docs/FR3.md, "Joint limits").
fn fr3_joints() -> [JointSpec; 6] {
    let joint = |name, lower_deg: f64, upper_deg: f64, max_velocity| JointSpec {
        name,
        lower: lower_deg * DEG,
        upper: upper_deg * DEG,
        max_velocity,
    };
    [
        joint("j1", -175.0, 175.0, 3.15),
        joint("j2", -265.0, 85.0, 3.15),
        joint("j3", -150.0, 150.0, 3.15),
        joint("j4", -265.0, 85.0, 3.2),
        joint("j5", -175.0, 175.0, 3.2),
        joint("j6", -175.0, 175.0, 3.2),
    ]
}

fn dh_table(d1: f64, a2: f64, a3: f64, d4: f64, d5: f64, d6: f64) -> [DhRow; 6] {
    [
        DhRow {
            d: d1,
            a: 0.0,
            alpha: FRAC_PI_2,
        },
        DhRow {
            d: 0.0,
            a: a2,
            alpha: 0.0,
        },
        DhRow {
            d: 0.0,
            a: a3,
            alpha: 0.0,
        },
        DhRow {
            d: d4,
            a: 0.0,
            alpha: FRAC_PI_2,
        },
        DhRow {
            d: d5,
            a: 0.0,
            alpha: -FRAC_PI_2,
        },
        DhRow {
            d: d6,
            a: 0.0,
            alpha: 0.0,
        },
    ]
}

/// Mesh-derived mass properties (the official URDF's arm inertias are 5–15× too small).
fn fr3_inertials() -> Vec<LinkInertial> {
    let link = |link, mass, com, inertia_diag| LinkInertial {
        link,
        mass,
        com,
        inertia_diag,
    };
    vec![
        link(
            "base_link",
            0.784,
            [0.0, 0.0, 0.033],
            [0.00138, 0.00138, 0.00197],
        ),
        link(
            "shoulder_link",
            2.123,
            [0.0, -0.0025, 0.135],
            [0.00356, 0.00348, 0.00230],
        ),
        link(
            "upperarm_link",
            4.805,
            [-0.141, 0.0, 0.111],
            [0.00809, 0.09135, 0.08862],
        ),
        link(
            "forearm_link",
            2.231,
            [-0.190, 0.0, 0.0034],
            [0.00306, 0.01836, 0.01758],
        ),
        link(
            "wrist1_link",
            1.596,
            [0.0, -0.0034, 0.098],
            [0.00216, 0.00145, 0.00206],
        ),
        link(
            "wrist2_link",
            1.596,
            [0.0, 0.0034, 0.098],
            [0.00216, 0.00145, 0.00206],
        ),
        link(
            "wrist3_link",
            0.539,
            [0.0, 0.0, 0.077],
            [0.00029, 0.00029, 0.00042],
        ),
    ]
}

/// One capsule per link, covering the real housings.
fn fr3_capsules() -> Vec<LinkCapsule> {
    let capsule = |link, from, to, radius| LinkCapsule {
        link,
        from,
        to,
        radius,
    };
    vec![
        capsule("base_link", [0.0, 0.0, 0.0], [0.0, 0.0, 0.080], 0.064),
        capsule(
            "shoulder_link",
            [0.0, -0.004, 0.11],
            [0.0, -0.004, 0.16],
            0.070,
        ),
        capsule(
            "upperarm_link",
            [0.0, 0.0, 0.110],
            [-0.28, 0.0, 0.110],
            0.075,
        ),
        capsule(
            "forearm_link",
            [0.0, 0.0, 0.005],
            [-0.24, 0.0, 0.005],
            0.065,
        ),
        capsule(
            "wrist1_link",
            [0.0, -0.02, 0.098],
            [0.0, 0.01, 0.098],
            0.065,
        ),
        capsule(
            "wrist2_link",
            [0.0, -0.01, 0.098],
            [0.0, 0.02, 0.098],
            0.065,
        ),
        capsule("wrist3_link", [0.0, 0.0, 0.06], [0.0, 0.0, 0.08], 0.045),
    ]
}

/// The parallel-jaw gripper (FAIRINO sells none): sized like a Robotiq 2F-85 / DH AG-95.
pub fn parallel_gripper() -> GripperSpec {
    GripperSpec {
        finger_travel: 0.0425,
        palm_size: [0.09, 0.06, 0.10],
        palm_mass: 0.75,
        finger_mass: 0.05,
        pad_size: [0.008, 0.022, 0.038],
        pad_friction: 0.8,
        grip_force: 20.0,
        tcp_offset: 0.14,
    }
}

/// Pairs FAIRINO's MoveIt configuration also ignores, beyond adjacent links.
const IGNORED_PAIRS: [(&str, &str); 3] = [
    ("base_link", "upperarm_link"),
    ("shoulder_link", "wrist1_link"),
    ("wrist1_link", "wrist3_link"),
];

impl ArmKind {
    /// The model with FAIRINO's numbers.
    pub fn model(self) -> ArmModel {
        match self {
            ArmKind::Fr3 => fr3(),
            ArmKind::Fr5 => fr5(),
        }
    }
}

/// The FAIRINO FR3 with the parallel-jaw gripper.
pub fn fr3() -> ArmModel {
    let gripper = parallel_gripper();
    ArmModel {
        kind: ArmKind::Fr3,
        dh: dh_table(0.140, -0.280, -0.240, 0.102, 0.102, 0.100),
        joints: fr3_joints(),
        links: LINK_NAMES,
        inertials: fr3_inertials(),
        capsules: fr3_capsules(),
        ignored_collision_pairs: IGNORED_PAIRS.to_vec(),
        tcp_in_flange: Pose::from_xyz([0.0, 0.0, gripper.tcp_offset]),
        gripper,
    }
}

/// The FAIRINO FR5: the FR3's structure with longer links.
///
/// Only its DH lengths are published (docs/FR3.md), so the FR3's joint and velocity limits are
/// used, and it has no mass properties or collision capsules: fitting capsules or inertias would
/// need the FR5's meshes, which the sources do not include. It serves kinematics; a physics
/// scene must refuse it ([`ArmModel::check_simulatable`] says what is missing).
pub fn fr5() -> ArmModel {
    let gripper = parallel_gripper();
    ArmModel {
        kind: ArmKind::Fr5,
        dh: dh_table(0.152, -0.425, -0.395, 0.102, 0.102, 0.100),
        joints: fr3_joints(),
        links: LINK_NAMES,
        inertials: Vec::new(),
        capsules: Vec::new(),
        ignored_collision_pairs: IGNORED_PAIRS.to_vec(),
        tcp_in_flange: Pose::from_xyz([0.0, 0.0, gripper.tcp_offset]),
        gripper,
    }
}
