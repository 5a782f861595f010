//! The pre-check's rules for a `<joint>` and an `<origin>`, each naming the line: what urdf-rs
//! would refuse without saying where (a missing `<parent>`, a `<limit>` without `velocity`, an
//! element given twice) or read differently from what the file means (`quat_xyzw` in a URDF 1.0
//! file, which urdf-rs ignores; a zero quaternion, which it turns into the identity).

use quick_xml::events::BytesStart;

use crate::urdf::error::UrdfError;
use crate::urdf::joint::JointKind;
use crate::urdf::xml::attribute;

/// The joint's child elements a URDF gives at most once, and which of them fairgrasp reads.
const JOINT_PARTS: [&str; 5] = ["parent", "child", "origin", "axis", "limit"];

/// A top-level `<joint>` whose end has not been read yet.
pub(crate) struct OpenJoint {
    pub name: String,
    pub kind: JointKind,
    /// Line of `<joint>`.
    pub line: usize,
    /// The parts ([`JOINT_PARTS`]) read so far.
    seen: Vec<&'static str>,
}

impl OpenJoint {
    pub fn new(name: String, kind: JointKind, line: usize) -> Self {
        Self {
            name,
            kind,
            line,
            seen: Vec::new(),
        }
    }
}

/// A [`UrdfError::Parse`] naming `line`.
pub(crate) fn at_line(file: &str, line: usize, message: String) -> UrdfError {
    UrdfError::Parse {
        file: file.to_string(),
        message: format!("line {line}: {message}"),
    }
}

/// Checks one child element `part` (on `line`) of `joint`: given once, `<parent>` and `<child>`
/// with a link, `<limit>` with a velocity.
pub(crate) fn check_joint_part(
    file: &str,
    line: usize,
    joint: &mut OpenJoint,
    part: &str,
    element: &BytesStart<'_>,
) -> Result<(), UrdfError> {
    let Some(&part) = JOINT_PARTS.iter().find(|p| **p == part) else {
        return Ok(());
    };
    let fault = |problem: &str| {
        let message = format!("joint '{}' <{part}>: {problem}", joint.name);
        Err(at_line(file, line, message))
    };
    if joint.seen.contains(&part) {
        return fault(&format!("given twice; a joint has one <{part}>"));
    }
    joint.seen.push(part);
    match part {
        "parent" | "child" if attribute(element, "link").is_none() => fault("no link attribute"),
        "limit" if attribute(element, "velocity").is_none() => {
            fault("no velocity attribute (URDF requires it)")
        }
        _ => Ok(()),
    }
}

/// At the joint's end: a `<limit>` where its type needs one, a `<parent>` and a `<child>`.
pub(crate) fn check_joint_end(file: &str, joint: &OpenJoint) -> Result<(), UrdfError> {
    let has = |part| joint.seen.contains(&part);
    if joint.kind.has_position_limits() && !has("limit") {
        return Err(UrdfError::MissingLimit {
            file: file.to_string(),
            line: joint.line,
            joint: joint.name.clone(),
            kind: joint.kind.name().to_string(),
        });
    }
    for role in ["parent", "child"] {
        if !has(role) {
            let message = format!("joint '{}' has no <{role} link=\"…\"/>", joint.name);
            return Err(at_line(file, joint.line, message));
        }
    }
    Ok(())
}

/// Does `<robot version>` allow `quat_xyzw` (URDF 1.1 and later)? A missing or malformed
/// version is 1.0, as urdf-rs and urdfdom read it.
pub(crate) fn allows_quaternions(robot: &BytesStart<'_>) -> bool {
    let version = attribute(robot, "version").and_then(|v| {
        let (major, minor) = v.trim().split_once('.')?;
        Some((major.parse::<u32>().ok()?, minor.parse::<u32>().ok()?))
    });
    version.unwrap_or((1, 0)) >= (1, 1)
}

/// An `<origin>` (of `owner`, on `line`) gives its rotation once, and as a quaternion only in a
/// URDF 1.1 file and not zero. Its numbers were checked (count, finite) before.
pub(crate) fn check_origin(
    file: &str,
    line: usize,
    owner: &str,
    element: &BytesStart<'_>,
    quaternions_allowed: bool,
) -> Result<(), UrdfError> {
    let Some(quat) = attribute(element, "quat_xyzw") else {
        return Ok(());
    };
    let fault = |problem: &str| Err(at_line(file, line, format!("{owner} <origin>: {problem}")));
    if attribute(element, "rpy").is_some() {
        return fault("both rpy and quat_xyzw; give one");
    }
    if !quaternions_allowed {
        return fault(
            "quat_xyzw is URDF 1.1; write <robot version=\"1.1\"> (a URDF 1.0 reader ignores it) or give rpy",
        );
    }
    let norm2: f64 = quat
        .split_whitespace()
        .filter_map(|t| t.parse::<f64>().ok())
        .map(|x| x * x)
        .sum();
    if norm2.sqrt() < 1e-12 {
        return fault("quat_xyzw is zero; a rotation needs a unit quaternion");
    }
    Ok(())
}
