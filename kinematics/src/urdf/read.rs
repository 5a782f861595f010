//! The second pass over URDF text, after [`check_urdf_text`](crate::urdf::check) accepted it:
//! the robot's name, its links and its joints as the file states them (`<origin>`, `<axis>`,
//! `<limit>`, `<parent>`, `<child>`), with URDF's defaults for what a joint leaves out (origin
//! zero, axis `1 0 0`, limits 0). Everything else in the file (visuals, collisions, inertials,
//! transmissions, vendor extensions) is skipped: nothing here needs it.
//!
//! One pass with quick-xml, no recursion. Errors name the line and the element; the numbers
//! were checked by the first pass (count and finiteness), so a number that still does not parse
//! is reported, never unwrapped.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::check::attribute;
use crate::urdf::error::UrdfError;

/// A joint as the file states it (before the tree is built and the axis normalised).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct JointText {
    pub name: String,
    /// A URDF joint type ([`JointKind::from_name`](crate::urdf::JointKind::from_name); checked by
    /// the first pass).
    pub kind: String,
    pub parent: String,
    pub child: String,
    /// `<origin xyz rpy>` [m, rad]; zero when absent.
    pub xyz: [f64; 3],
    pub rpy: [f64; 3],
    /// `<axis xyz>`; `1 0 0` when absent.
    pub axis: [f64; 3],
    /// `<limit lower upper velocity effort>`; 0 for each one absent.
    pub lower: f64,
    pub upper: f64,
    pub velocity: f64,
    pub effort: f64,
    /// Line of `<joint>`, for messages.
    pub line: usize,
}

/// The robot as the file states it.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct RobotText {
    pub name: String,
    /// Link names in file order.
    pub links: Vec<String>,
    pub joints: Vec<JointText>,
}

/// Reads the robot out of `text`, which [`check_urdf_text`](crate::urdf::check) accepted.
pub(crate) fn read_robot(file: &str, text: &str) -> Result<RobotText, UrdfError> {
    let parse = |line: usize, message: String| UrdfError::Parse {
        file: file.to_string(),
        message: format!("line {line}: {message}"),
    };
    let mut reader = Reader::from_str(text);
    let mut robot: Option<RobotText> = None;
    let mut joint: Option<JointText> = None;
    let mut depth = 0usize;
    let mut line = 1usize;
    let mut counted = 0usize;
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader
            .read_event()
            .map_err(|e| parse(line, e.to_string()))?;
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
        // Lines counted incrementally (the offsets only grow).
        let upto = start.clamp(counted, text.len());
        line += text.as_bytes()[counted..upto]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        counted = upto;
        let level = depth + 1;
        if !is_empty {
            depth += 1;
        }
        let tag = element.name();
        let tag = String::from_utf8_lossy(tag.as_ref()).into_owned();
        match (level, tag.as_str()) {
            (1, "robot") => {
                let name = attribute(element, "name")
                    .ok_or_else(|| parse(line, "<robot> has no name attribute".into()))?;
                robot = Some(RobotText {
                    name,
                    links: Vec::new(),
                    joints: Vec::new(),
                });
            }
            (1, other) => {
                return Err(parse(
                    line,
                    format!("the root element is <{other}>; a URDF's is <robot>"),
                ));
            }
            (2, "link") => {
                let name = attribute(element, "name")
                    .ok_or_else(|| parse(line, "a <link> has no name attribute".into()))?;
                if let Some(r) = robot.as_mut() {
                    r.links.push(name);
                }
            }
            (2, "joint") => {
                let name = attribute(element, "name")
                    .ok_or_else(|| parse(line, "a <joint> has no name attribute".into()))?;
                let kind = attribute(element, "type").unwrap_or_default();
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
                };
                match (is_empty, robot.as_mut()) {
                    (true, Some(r)) => r.joints.push(j),
                    _ => joint = Some(j),
                }
            }
            (3, part) => {
                if let Some(j) = joint.as_mut() {
                    read_joint_part(j, part, element)
                        .map_err(|m| parse(line, format!("joint '{}' <{part}>: {m}", j.name)))?;
                }
            }
            _ => {}
        }
    }
    let robot = robot.ok_or_else(|| parse(line, "no <robot> element".into()))?;
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
    match part {
        "parent" | "child" => {
            let link = attribute(element, "link").ok_or("no link attribute")?;
            *(if part == "parent" {
                &mut j.parent
            } else {
                &mut j.child
            }) = link;
        }
        "origin" => {
            j.xyz = numbers(element, "xyz")?.unwrap_or([0.0; 3]);
            j.rpy = numbers(element, "rpy")?.unwrap_or([0.0; 3]);
        }
        "axis" => j.axis = numbers(element, "xyz")?.unwrap_or([1.0, 0.0, 0.0]),
        "limit" => {
            let one = |key| numbers::<1>(element, key).map(|v| v.map_or(0.0, |[x]| x));
            j.lower = one("lower")?;
            j.upper = one("upper")?;
            j.velocity = one("velocity")?;
            j.effort = one("effort")?;
        }
        _ => {}
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
