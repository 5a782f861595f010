//! Reading a URDF into its joint table ([`UrdfRobot`]) and picking a serial chain from it.
//!
//! Text goes through the pre-check (`check.rs`), then urdf-rs, then the mapping into
//! fairgrasp's model (`map.rs`), then the tree's checks here. Errors name the file, the element
//! and the value at fault. Reading and checking take time linear in the file's length (every
//! look-up by name goes through a hash map), and files larger than [`MAX_URDF_BYTES`] or nested
//! deeper than [`MAX_NESTING_DEPTH`](crate::urdf::MAX_NESTING_DEPTH) are refused.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use crate::urdf::chain::SerialChain;
use crate::urdf::check::{MAX_URDF_BYTES, check_urdf_text};
use crate::urdf::error::UrdfError;
use crate::urdf::joint::{JointKind, UrdfJoint};
use crate::urdf::locate::locate;
use crate::urdf::map::{Mapped, map_robot};

/// A parsed robot: its joints in depth-first order from the root link.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfRobot {
    /// The file it came from (or `"<string>"`), for messages.
    pub file: String,
    /// `<robot name>`.
    pub name: String,
    /// The root link.
    pub root: String,
    /// Every link name, in file order.
    pub links: Vec<String>,
    /// Every joint, depth-first from the root.
    pub joints: Vec<UrdfJoint>,
}

impl UrdfRobot {
    /// Reads and checks a URDF file of at most [`MAX_URDF_BYTES`].
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, UrdfError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let limit = MAX_URDF_BYTES as u64;
        // Only a regular file within the cap is opened, by the rule every input follows: a FIFO
        // would block, a device never ends.
        let text =
            fairgrasp_types::fs::read_text_bounded(path, limit).map_err(
                |e| match std::fs::metadata(path) {
                    Ok(m) if m.is_file() && m.len() > limit => UrdfError::TooLarge {
                        file: file.clone(),
                        bytes: m.len(),
                        limit,
                    },
                    _ => UrdfError::Read {
                        file: file.clone(),
                        message: e.to_string(),
                    },
                },
            )?;
        Self::from_str_named(&text, &file)
    }

    /// Parses URDF text of at most [`MAX_URDF_BYTES`]; `file` names it in error messages.
    pub fn from_str_named(text: &str, file: &str) -> Result<Self, UrdfError> {
        check_urdf_text(file, text)?;
        let robot =
            urdf_rs::read_from_string(text).map_err(|e| locate(file, text, &e.to_string()))?;
        Self::from_urdf_rs(&robot, file)
    }

    /// The joint table of a robot urdf-rs read (`file` names it in error messages), with the
    /// same checks as text gets after the pre-check: finite numbers, non-zero axes, ordered
    /// limits, one tree. No line is named: a `urdf_rs::Robot` keeps none.
    pub fn from_urdf_rs(robot: &urdf_rs::Robot, file: &str) -> Result<Self, UrdfError> {
        build_tree(file, map_robot(file, robot)?)
    }

    /// Joints with one degree of freedom, in tree order.
    pub fn movable_joints(&self) -> impl Iterator<Item = &UrdfJoint> {
        self.joints.iter().filter(|j| j.kind.is_single_axis())
    }

    /// The chain from the root to `tip`, or to the only leaf when `tip` is `None`.
    pub fn chain(&self, tip: Option<&str>) -> Result<SerialChain, UrdfError> {
        let by_child: HashMap<&str, &UrdfJoint> =
            self.joints.iter().map(|j| (j.child.as_str(), j)).collect();
        let tip = match tip {
            Some(tip) if self.links.iter().any(|l| l == tip) => tip.to_string(),
            Some(tip) => {
                return Err(UrdfError::UnknownLink {
                    file: self.file.clone(),
                    link: tip.to_string(),
                    known: self.links.clone(),
                });
            }
            None => self.only_leaf()?,
        };
        let mut joints = Vec::new();
        let mut link = tip.as_str();
        while let Some(joint) = by_child.get(link) {
            if !joint.kind.is_single_axis() && joint.kind != JointKind::Fixed {
                return Err(UrdfError::UnsupportedJoint {
                    file: self.file.clone(),
                    joint: joint.name.clone(),
                    kind: joint.kind.name().to_string(),
                });
            }
            joints.push((*joint).clone());
            link = &joint.parent;
        }
        joints.reverse();
        Ok(SerialChain { joints, tip })
    }

    fn only_leaf(&self) -> Result<String, UrdfError> {
        let children_of = child_joints(&self.joints);
        let mut link = self.root.as_str();
        loop {
            let children = children_of.get(link).map_or(&[][..], Vec::as_slice);
            match children {
                [] => return Ok(link.to_string()),
                [only] => link = &only.child,
                many => {
                    return Err(UrdfError::NonSerial {
                        file: self.file.clone(),
                        link: link.to_string(),
                        children: many.iter().map(|&j| j.name.clone()).collect(),
                    });
                }
            }
        }
    }
}

/// The joints whose parent is each link, in the order of `joints`.
fn child_joints(joints: &[UrdfJoint]) -> HashMap<&str, Vec<&UrdfJoint>> {
    let mut children: HashMap<&str, Vec<&UrdfJoint>> = HashMap::new();
    for joint in joints {
        children.entry(&joint.parent).or_default().push(joint);
    }
    children
}

fn build_tree(file: &str, robot: Mapped) -> Result<UrdfRobot, UrdfError> {
    let links = robot.links;
    let known_links: HashSet<&str> = links.iter().map(String::as_str).collect();
    let mut parent_of: HashMap<&str, &str> = HashMap::new();
    for j in &robot.joints {
        for (role, link) in [("parent", &j.parent), ("child", &j.child)] {
            if !known_links.contains(link.as_str()) {
                return Err(UrdfError::MissingLink {
                    file: file.to_string(),
                    joint: j.name.clone(),
                    role,
                    link: link.clone(),
                });
            }
        }
        if let Some(other) = parent_of.insert(&j.child, &j.name) {
            return Err(UrdfError::NotATree {
                file: file.to_string(),
                detail: format!(
                    "link '{}' is the child of two joints, '{other}' and '{}'",
                    j.child, j.name
                ),
            });
        }
    }
    let roots: Vec<&String> = links
        .iter()
        .filter(|l| !parent_of.contains_key(l.as_str()))
        .collect();
    let [root] = roots.as_slice() else {
        let detail = if roots.is_empty() {
            "no root link (the joints form a cycle)".to_string()
        } else {
            format!(
                "{} root links ({}); one is expected",
                roots.len(),
                fairgrasp_types::text::first_few(&roots, 5)
            )
        };
        return Err(UrdfError::NotATree {
            file: file.to_string(),
            detail,
        });
    };
    // Depth-first from the root; joints never reached sit on a cycle.
    let joints = depth_first(&robot.joints, root);
    if joints.len() != robot.joints.len() {
        return Err(UrdfError::NotATree {
            file: file.to_string(),
            detail: "some joints are not reachable from the root link (a cycle)".to_string(),
        });
    }
    Ok(UrdfRobot {
        file: file.to_string(),
        name: robot.name,
        root: root.to_string(),
        links,
        joints,
    })
}

/// The joints reachable from `root`, each right after the branch that leads to it (pre-order,
/// siblings in file order). An explicit stack, not recursion: a chain of thousands of joints
/// must not overflow the call stack.
fn depth_first(pool: &[UrdfJoint], root: &str) -> Vec<UrdfJoint> {
    let children_of = child_joints(pool);
    let children = |link: &str| children_of.get(link).map_or(&[][..], Vec::as_slice);
    let mut ordered = Vec::with_capacity(pool.len());
    let mut stack: Vec<&UrdfJoint> = children(root).iter().rev().copied().collect();
    while let Some(joint) = stack.pop() {
        ordered.push(joint.clone());
        if ordered.len() > pool.len() {
            break; // a cycle below the root; the caller reports it
        }
        stack.extend(children(&joint.child).iter().rev());
    }
    ordered
}
