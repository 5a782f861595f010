//! The arm model type: DH table, joint limits, masses, collision capsules, flange and TCP.
//!
//! The numbers themselves live in [`crate::fairino`] (with [`ArmKind::model`], which picks an
//! arm's numbers); this module only says what they mean.

use crate::pose::Pose;

/// Which arm: the FAIRINO models fairgrasp knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArmKind {
    /// FAIRINO FR3: 3 kg payload, 0.622 m reach.
    Fr3,
    /// FAIRINO FR5: 5 kg payload, same structure, longer links.
    Fr5,
}

impl ArmKind {
    /// Every model, for `--help` texts and error messages.
    pub const ALL: [ArmKind; 2] = [ArmKind::Fr3, ArmKind::Fr5];

    /// Lower-case name as used on the command line ("fr3", "fr5").
    pub fn name(self) -> &'static str {
        match self {
            ArmKind::Fr3 => "fr3",
            ArmKind::Fr5 => "fr5",
        }
    }

    /// Parses "fr3" / "fr5" (case-insensitive).
    pub fn parse(name: &str) -> Option<ArmKind> {
        ArmKind::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(name))
    }
}

/// Data a physics simulation of the arm needs that the model lacks (the FR5: FAIRINO publishes
/// only its DH lengths, see `docs/FR3.md`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MissingModelData {
    /// The arm.
    pub arm: ArmKind,
    /// What is missing, e.g. `["collision capsules", "mass properties"]`.
    pub missing: Vec<&'static str>,
}

impl std::fmt::Display for MissingModelData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the {} model has no {} (the maker publishes none; see docs/FR3.md): it serves \
             kinematics (fk, ik, frames) but cannot be simulated in the grasping environment; \
             use the fr3",
            self.arm.name().to_uppercase(),
            self.missing.join(" and no ")
        )
    }
}

impl std::error::Error for MissingModelData {}

/// One row of a standard (distal) DH table: `T_i = Rz(θ_i)·Tz(d)·Tx(a)·Rx(α)`, θ offset 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DhRow {
    /// Offset along the previous z axis \[m\].
    pub d: f64,
    /// Length along the new x axis \[m\].
    pub a: f64,
    /// Twist about the new x axis \[rad\].
    pub alpha: f64,
}

/// One revolute joint's name and limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointSpec {
    /// URDF joint name ("j1" … "j6").
    pub name: &'static str,
    /// Lower position limit \[rad\] (the manual's soft limit).
    pub lower: f64,
    /// Upper position limit \[rad\] (the manual's soft limit).
    pub upper: f64,
    /// Velocity limit \[rad/s\].
    pub max_velocity: f64,
}

impl JointSpec {
    /// Is `q` \[rad\] within `[lower, upper]`, allowing `tolerance` \[rad\] on either side?
    pub fn contains(&self, q: f64, tolerance: f64) -> bool {
        q >= self.lower - tolerance && q <= self.upper + tolerance
    }
}

/// Mass properties of one link, about its centre of mass, in the link's (URDF) frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkInertial {
    /// URDF link name.
    pub link: &'static str,
    /// Mass \[kg\].
    pub mass: f64,
    /// Centre of mass in the link frame \[m\].
    pub com: [f64; 3],
    /// Principal moments `ixx, iyy, izz` about the CoM \[kg·m²\] (off-diagonal terms are zero).
    pub inertia_diag: [f64; 3],
}

/// A capsule collision shape: the segment `from → to` in the link frame \[m\], swept by
/// `radius` \[m\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkCapsule {
    /// URDF link name.
    pub link: &'static str,
    /// First end point of the axis segment, link frame \[m\].
    pub from: [f64; 3],
    /// Second end point of the axis segment, link frame \[m\].
    pub to: [f64; 3],
    /// Radius \[m\].
    pub radius: f64,
}

/// The parallel-jaw gripper mounted on `tool0` (sized like a Robotiq 2F-85 / DH AG-95).
///
/// Frame: `tool0` z points out of the flange; the fingers move along `tool0` x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GripperSpec {
    /// Travel of each finger from fully open (0) to fully closed \[m\].
    pub finger_travel: f64,
    /// Palm box size `x, y, z` \[m\]; the palm spans z ∈ [0, size.z] in `tool0`.
    pub palm_size: [f64; 3],
    /// Palm mass \[kg\].
    pub palm_mass: f64,
    /// Mass of one finger including its pad \[kg\].
    pub finger_mass: f64,
    /// Pad size `x` (thickness, along the closing direction), `y` (width), `z` (height) \[m\].
    pub pad_size: [f64; 3],
    /// Pad friction coefficient.
    pub pad_friction: f64,
    /// Default grip force per finger \[N\].
    pub grip_force: f64,
    /// TCP (between the pad centres) in `tool0` \[m\]: along `tool0` z.
    pub tcp_offset: f64,
}

impl GripperSpec {
    /// Distance between the pads' inner faces for a finger travel `q` \[m\] (same on both fingers).
    pub fn opening(&self, q: f64) -> f64 {
        2.0 * (self.finger_travel - q)
    }
}

/// A six-axis UR-like arm: everything kinematics, dynamics and collision checking need.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmModel {
    /// Which arm this is.
    pub kind: ArmKind,
    /// Standard DH table; frame 6 is the flange (`tool0`).
    pub dh: [DhRow; 6],
    /// Joint names and limits, j1 … j6.
    pub joints: [JointSpec; 6],
    /// URDF link names, base_link … wrist3_link.
    pub links: [&'static str; 7],
    /// Mass properties per link (empty where the maker publishes none).
    pub inertials: Vec<LinkInertial>,
    /// One collision capsule per link (empty where none is published).
    pub capsules: Vec<LinkCapsule>,
    /// Non-adjacent link pairs whose collisions are ignored (adjacent pairs always are).
    pub ignored_collision_pairs: Vec<(&'static str, &'static str)>,
    /// The gripper on `tool0`.
    pub gripper: GripperSpec,
    /// `T_tool0_tcp`: the tool centre point in the flange frame.
    pub tcp_in_flange: Pose,
}

impl ArmModel {
    /// Lower joint limits \[rad\].
    pub fn lower_limits(&self) -> [f64; 6] {
        self.joints.map(|j| j.lower)
    }

    /// Upper joint limits \[rad\].
    pub fn upper_limits(&self) -> [f64; 6] {
        self.joints.map(|j| j.upper)
    }

    /// Velocity limits \[rad/s\].
    pub fn velocity_limits(&self) -> [f64; 6] {
        self.joints.map(|j| j.max_velocity)
    }

    /// Are all joints within their limits (± `tolerance` rad)?
    pub fn in_limits(&self, q: &[f64; 6], tolerance: f64) -> bool {
        self.joints
            .iter()
            .zip(q)
            .all(|(j, &qi)| j.contains(qi, tolerance))
    }

    /// The first joint outside its limits, as (index, value), if any.
    pub fn first_limit_violation(&self, q: &[f64; 6]) -> Option<(usize, f64)> {
        self.joints
            .iter()
            .zip(q)
            .position(|(j, &qi)| !j.contains(qi, 0.0))
            .map(|i| (i, q[i]))
    }

    /// Maximum reach of the wrist from the shoulder, `|a2| + |a3| + d5` \[m\].
    pub fn reach(&self) -> f64 {
        self.dh[1].a.abs() + self.dh[2].a.abs() + self.dh[4].d
    }

    /// Height of the shoulder point (joint 2 axis) above `base_link` \[m\].
    pub fn shoulder_height(&self) -> f64 {
        self.dh[0].d
    }

    /// Does every link have its collision capsule, in link order (`capsules[i]` belongs to
    /// `links[i]`, as a scene built from the model indexes them)?
    pub fn has_collision_model(&self) -> bool {
        self.capsules.len() == self.links.len()
            && self
                .capsules
                .iter()
                .zip(&self.links)
                .all(|(c, l)| c.link == *l)
    }

    /// Does every link have its mass properties, in link order, with a positive mass?
    pub fn has_mass_model(&self) -> bool {
        self.inertials.len() == self.links.len()
            && self
                .inertials
                .iter()
                .zip(&self.links)
                .all(|(m, l)| m.link == *l && m.mass > 0.0)
    }

    /// `Ok` when the model has everything a physics scene needs (capsules and masses for every
    /// link); otherwise what is missing. An environment calls this before building a scene.
    pub fn check_simulatable(&self) -> Result<(), MissingModelData> {
        let mut missing = Vec::new();
        if !self.has_collision_model() {
            missing.push("collision capsules");
        }
        if !self.has_mass_model() {
            missing.push("mass properties");
        }
        if missing.is_empty() {
            Ok(())
        } else {
            Err(MissingModelData {
                arm: self.kind,
                missing,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fr3_is_simulatable_and_the_fr5_is_refused_with_what_it_lacks() {
        assert_eq!(ArmKind::Fr3.model().check_simulatable(), Ok(()));
        let e = ArmKind::Fr5.model().check_simulatable().unwrap_err();
        assert_eq!(e.missing, vec!["collision capsules", "mass properties"]);
        let text = e.to_string();
        assert!(
            text.starts_with("the FR5 model has no collision capsules and no mass properties"),
            "{text}"
        );
        assert!(
            text.contains("docs/FR3.md") && text.contains("use the fr3"),
            "{text}"
        );
    }

    #[test]
    fn capsules_or_masses_out_of_link_order_do_not_count_as_a_model() {
        let mut m = ArmKind::Fr3.model();
        m.capsules.swap(1, 2);
        assert!(!m.has_collision_model());
        assert!(m.has_mass_model());
        let mut m = ArmKind::Fr3.model();
        m.inertials[3].mass = 0.0;
        assert!(!m.has_mass_model());
        assert_eq!(
            m.check_simulatable().unwrap_err().missing,
            vec!["mass properties"]
        );
    }
}
