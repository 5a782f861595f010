//! The second pass over URDF text, after [`check_urdf_text`](crate::urdf::check) accepted it:
//! the robot's name, its links and its joints as the file states them (`<origin>`, `<axis>`,
//! `<limit>`, `<parent>`, `<child>`). Everything else in the file (visuals, collisions,
//! inertials, transmissions, vendor extensions) is skipped: nothing here needs it.
//!
//! What a joint leaves out takes URDF's defaults: no `<origin>` is the identity, no `<axis>` (or
//! one without `xyz`) is `1 0 0`, a `<limit>` without `lower`, `upper` or `effort` has 0 there;
//! `velocity` has no default (URDF requires it, as urdf-rs did). A `<robot>` without a name is
//! named "". URDF 1.1's `<origin quat_xyzw>` is read as the rotation it gives (in place of
//! `rpy`; giving both is refused). A joint's `<parent>`, `<child>`, `<origin>`, `<axis>` or
//! `<limit>` given twice is refused, naming its line.
//!
//! One pass with quick-xml, no recursion. The numbers were checked by the first pass (count and
//! finiteness), so a number that still does not parse is reported, never unwrapped.

use nalgebra::{Quaternion, UnitQuaternion};
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::check::{LineCounter, attribute};
use crate::urdf::error::UrdfError;
use crate::urdf::joint::JointKind;

/// A joint as the file states it (before the tree is built and the axis normalised).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointText {
    pub name: String,
    pub kind: JointKind,
    pub parent: String,
    pub child: String,
    /// `<origin xyz rpy>` \[m, rad\].
    pub xyz: [f64; 3],
    pub rpy: [f64; 3],
    /// `<axis xyz>`.
    pub axis: [f64; 3],
    /// `<limit lower upper velocity effort>` \[rad or m, rad/s or m/s, N·m or N\].
    pub lower: f64,
    pub upper: f64,
    pub velocity: f64,
    pub effort: f64,
    /// Line of `<joint>`, for messages.
    pub line: usize,
    /// The child elements read so far (each at most once).
    seen: Vec<&'static str>,
}

/// The robot as the file states it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RobotText {
    pub name: String,
    /// Link names in file order.
    pub links: Vec<String>,
    pub joints: Vec<JointText>,
}

/// The joint's child elements this pass reads.
const JOINT_PARTS: [&str; 5] = ["parent", "child", "origin", "axis", "limit"];

/// Reads the robot out of `text`, which [`check_urdf_text`](crate::urdf::check) accepted.
pub(crate) fn read_robot(file: &str, text: &str) -> Result<RobotText, UrdfError> {
    let parse = |line: usize, message: String| UrdfError::Parse {
        file: file.to_string(),
        message: format!("line {line}: {message}"),
    };
    let mut reader = Reader::from_str(text);
    let mut lines = LineCounter::new(text);
    let mut robot: Option<RobotText> = None;
    let mut joint: Option<JointText> = None;
    let mut depth = 0usize;
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader.read_event().map_err(|e| {
            parse(
                lines.line_at(reader.error_position() as usize),
                e.to_string(),
            )
        })?;
        let (element, is_empty) = match &event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                depth = depth.saturating_sub(1);
                if depth == 1
                    && let (Some(j), Some(r)) = (joint.take(), robot.as_mut())
                {
                    r.joints.push(j);
                }
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let line = lines.line_at(start);
        let level = depth + 1;
        if !is_empty {
            depth += 1;
        }
        let tag = element.name();
        let tag = String::from_utf8_lossy(tag.as_ref()).into_owned();
        match (level, tag.as_str(), robot.as_mut()) {
            (1, "robot", None) => {
                robot = Some(RobotText {
                    name: attribute(element, "name").unwrap_or_default(),
                    links: Vec::new(),
                    joints: Vec::new(),
                });
            }
            (1, other, _) => {
                let what = if robot.is_some() {
                    format!("a second root element <{other}>; a URDF has one <robot>")
                } else {
                    format!("the root element is <{other}>; a URDF's is <robot>")
                };
                return Err(parse(line, what));
            }
            (2, "link", Some(r)) => {
                let name = attribute(element, "name")
                    .ok_or_else(|| parse(line, "a <link> has no name attribute".into()))?;
                r.links.push(name);
            }
            (2, "joint", Some(r)) => {
                let name = attribute(element, "name")
                    .ok_or_else(|| parse(line, "a <joint> has no name attribute".into()))?;
                // The first pass accepted the type.
                let kind = attribute(element, "type")
                    .as_deref()
                    .and_then(JointKind::from_name)
                    .ok_or_else(|| parse(line, format!("joint '{name}' has no valid type")))?;
                let j = JointText {
                    name,
                    kind,
                    parent: String::new(),
                    child: String::new(),
                    xyz: [0.0; 3],
                    rpy: [0.0; 3],
                    axis: [1.0, 0.0, 0.0],
                    lower: 0.0,
                    upper: 0.0,
                    velocity: 0.0,
                    effort: 0.0,
                    line,
                    seen: Vec::new(),
                };
                if is_empty {
                    r.joints.push(j);
                } else {
                    joint = Some(j);
                }
            }
            (3, part, _) => {
                if let Some(j) = joint.as_mut() {
                    read_joint_part(j, part, element)
                        .map_err(|m| parse(line, format!("joint '{}' <{part}>: {m}", j.name)))?;
                }
            }
            _ => {}
        }
    }
    let robot = robot.ok_or_else(|| parse(1, "no <robot> element".into()))?;
    for j in &robot.joints {
        for (role, link) in [("parent", &j.parent), ("child", &j.child)] {
            if link.is_empty() {
                return Err(parse(
                    j.line,
                    format!("joint '{}' has no <{role} link=\"…\"/>", j.name),
                ));
            }
        }
    }
    Ok(robot)
}

/// Reads one child element of a `<joint>` into `j`.
fn read_joint_part(j: &mut JointText, part: &str, element: &BytesStart<'_>) -> Result<(), String> {
    let Some(&part) = JOINT_PARTS.iter().find(|p| **p == part) else {
        return Ok(());
    };
    if j.seen.contains(&part) {
        return Err(format!("given twice; a joint has one <{part}>"));
    }
    j.seen.push(part);
    match part {
        "parent" => j.parent = attribute(element, "link").ok_or("no link attribute")?,
        "child" => j.child = attribute(element, "link").ok_or("no link attribute")?,
        "origin" => {
            j.xyz = numbers(element, "xyz")?.unwrap_or([0.0; 3]);
            let rpy = numbers::<3>(element, "rpy")?;
            j.rpy = match (rpy, numbers::<4>(element, "quat_xyzw")?) {
                (Some(_), Some(_)) => return Err("both rpy and quat_xyzw; give one".into()),
                (Some(rpy), None) => rpy,
                (None, Some([x, y, z, w])) => {
                    let q = Quaternion::new(w, x, y, z);
                    if q.norm() < 1e-12 {
                        return Err("quat_xyzw is zero; a rotation needs a unit quaternion".into());
                    }
                    let (roll, pitch, yaw) = UnitQuaternion::from_quaternion(q).euler_angles();
                    [roll, pitch, yaw]
                }
                (None, None) => [0.0; 3],
            };
        }
        "axis" => j.axis = numbers(element, "xyz")?.unwrap_or([1.0, 0.0, 0.0]),
        _ => {
            let one = |key| numbers::<1>(element, key).map(|v| v.map(|[x]| x));
            j.lower = one("lower")?.unwrap_or(0.0);
            j.upper = one("upper")?.unwrap_or(0.0);
            j.effort = one("effort")?.unwrap_or(0.0);
            j.velocity = one("velocity")?.ok_or("no velocity attribute (URDF requires it)")?;
        }
    }
    Ok(())
}

/// `N` numbers separated by spaces in attribute `key`, if present.
fn numbers<const N: usize>(
    element: &BytesStart<'_>,
    key: &str,
) -> Result<Option<[f64; N]>, String> {
    let Some(value) = attribute(element, key) else {
        return Ok(None);
    };
    let mut out = [0.0; N];
    let mut parts = value.split_whitespace();
    for slot in &mut out {
        *slot = parts
            .next()
            .and_then(|t| t.parse::<f64>().ok())
            .ok_or_else(|| format!("{key}=\"{value}\": expected {N} numbers"))?;
    }
    if parts.next().is_some() {
        return Err(format!("{key}=\"{value}\": expected {N} numbers"));
    }
    Ok(Some(out))
}
