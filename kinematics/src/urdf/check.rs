//! The pre-check: one pass over URDF text, before urdf-rs reads it, that names the offending
//! element, attribute and line (urdf-rs names none).
//!
//! This pass reads the XML once, in time linear in its length and with no recursion, and reports
//! the first fault as `line N: joint 'j2' <origin> xyz="0 0 abc": …`. It checks
//! - the size ([`MAX_URDF_BYTES`]) and the nesting depth ([`MAX_NESTING_DEPTH`]), and that no
//!   `<!DOCTYPE>` declares entities (fairgrasp expands none),
//! - that the one root element is `<robot>`,
//! - every link's and joint's name, and that no two links and no two joints share one,
//! - every joint's type, its `<parent>`, `<child>` and (revolute, prismatic) `<limit>`
//!   ([`check_joint`](crate::urdf::check_joint)),
//! - every numeric attribute: the count of numbers, each of them finite, and every `<origin>`'s
//!   rotation.
//!
//! What urdf-rs still refuses after this pass is located by
//! [`locate`](crate::urdf::locate).

use std::collections::HashMap;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::check_joint::{
    OpenJoint, allows_quaternions, at_line, check_joint_end, check_joint_part, check_origin,
};
use crate::urdf::error::UrdfError;
use crate::urdf::joint::JointKind;
use crate::urdf::xml::attribute;

/// The largest URDF text read \[bytes\]. A URDF names its mesh files rather than holding them:
/// the shipped FR3 file is 8 kB, a humanoid's a few hundred kB.
pub const MAX_URDF_BYTES: usize = 16 * 1024 * 1024;

/// The deepest element nesting read, `<robot>` being level 1. A URDF needs about 6
/// (`robot > link > visual > geometry > mesh`); vendor extensions a few more.
pub const MAX_NESTING_DEPTH: usize = 64;

/// How many numbers an attribute holds, by element and attribute name.
fn numeric_arity(element: &str, attribute: &str) -> Option<usize> {
    match (element, attribute) {
        ("origin", "xyz" | "rpy") | ("axis", "xyz") | ("box", "size") | ("mesh", "scale") => {
            Some(3)
        }
        ("color", "rgba") | ("origin", "quat_xyzw") => Some(4),
        ("limit", "lower" | "upper" | "effort" | "velocity")
        | ("mass", "value")
        | ("inertia", "ixx" | "ixy" | "ixz" | "iyy" | "iyz" | "izz")
        | ("cylinder" | "capsule", "radius" | "length")
        | ("sphere", "radius")
        | ("mimic", "multiplier" | "offset")
        | ("dynamics", "damping" | "friction")
        | ("calibration", "rising" | "falling")
        | ("safety_controller", _) => Some(1),
        _ => None,
    }
}

/// Line numbers of offsets, LF, CRLF and CR (old-Mac) line ends alike: the one counter.
pub(crate) use fairgrasp_types::text::LineCounter;

/// The first line each link name and each joint name was defined on.
#[derive(Default)]
struct NamesSeen {
    links: HashMap<String, usize>,
    joints: HashMap<String, usize>,
}

/// Where the pass is: the elements open, the names seen, the joint being read.
struct Walk {
    /// The elements opened and not yet closed: name and line, outermost first.
    open_elements: Vec<(String, usize)>,
    /// The root elements read (one is `<robot>`).
    roots: usize,
    /// Does `<robot version>` allow `quat_xyzw`?
    quaternions_allowed: bool,
    /// The top-level element being read, as messages name it (`joint 'j2'`).
    owner: String,
    names: NamesSeen,
    open_joint: Option<OpenJoint>,
    /// A top-level `<link>` or `<joint>` without a name: its tag and line.
    nameless: Option<(String, usize)>,
}

/// Checks size, entities, nesting, the root, names, joints and numeric attributes; `file` is
/// only used in messages.
pub fn check_urdf_text(file: &str, text: &str) -> Result<(), UrdfError> {
    if text.len() > MAX_URDF_BYTES {
        return Err(UrdfError::TooLarge {
            file: file.to_string(),
            bytes: text.len() as u64,
            limit: MAX_URDF_BYTES as u64,
        });
    }
    let mut reader = Reader::from_str(text);
    let mut lines = LineCounter::new(text);
    let mut walk = Walk {
        open_elements: Vec::new(),
        roots: 0,
        quaternions_allowed: false,
        owner: String::from("robot"),
        names: NamesSeen::default(),
        open_joint: None,
        nameless: None,
    };
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader.read_event().map_err(|e| UrdfError::Xml {
            file: file.to_string(),
            line: lines.line_at(reader.error_position() as usize),
            message: e.to_string(),
        })?;
        let (element, is_empty) = match &event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                walk.open_elements.pop();
                if walk.open_elements.len() == 1 {
                    check_named(file, &mut walk)?;
                    if let Some(joint) = walk.open_joint.take() {
                        check_joint_end(file, &joint)?;
                    }
                }
                continue;
            }
            Event::DocType(d) if d.windows(8).any(|w| w == b"<!ENTITY") => {
                let message = "the <!DOCTYPE> declares entities (<!ENTITY …>); a URDF needs \
                               none and fairgrasp expands none";
                return Err(at_line(file, lines.line_at(start), message.to_string()));
            }
            Event::Eof => return check_end(file, &walk),
            _ => continue,
        };
        check_element(file, lines.line_at(start), element, is_empty, &mut walk)?;
    }
}

/// Checks one element that starts on `line` (`is_empty`: written `<…/>`).
fn check_element(
    file: &str,
    line: usize,
    element: &BytesStart<'_>,
    is_empty: bool,
    walk: &mut Walk,
) -> Result<(), UrdfError> {
    let name = String::from_utf8_lossy(element.name().as_ref()).into_owned();
    let level = walk.open_elements.len() + 1;
    if level > MAX_NESTING_DEPTH {
        return Err(UrdfError::TooDeep {
            file: file.to_string(),
            line,
            element: name,
            depth: level,
            limit: MAX_NESTING_DEPTH,
        });
    }
    if !is_empty {
        walk.open_elements.push((name.clone(), line));
    }
    match level {
        1 => check_root(file, line, &name, element, walk)?,
        2 => check_top_level(file, line, &name, element, is_empty, walk)?,
        3 => {
            if let Some(joint) = walk.open_joint.as_mut() {
                check_joint_part(file, line, joint, &name, element)?;
            }
        }
        _ => {}
    }
    check_numbers(file, line, &walk.owner, &name, element)?;
    if name == "origin" {
        check_origin(file, line, &walk.owner, element, walk.quaternions_allowed)?;
    }
    Ok(())
}

/// The root element: one, and `<robot>`.
fn check_root(
    file: &str,
    line: usize,
    name: &str,
    element: &BytesStart<'_>,
    walk: &mut Walk,
) -> Result<(), UrdfError> {
    walk.roots += 1;
    if walk.roots > 1 {
        let message = format!("a second root element <{name}>; a URDF has one <robot>");
        return Err(at_line(file, line, message));
    }
    if name != "robot" {
        let message = format!("the root element is <{name}>; a URDF's is <robot>");
        return Err(at_line(file, line, message));
    }
    walk.quaternions_allowed = allows_quaternions(element);
    Ok(())
}

/// A direct child of `<robot>`: a link, a joint, a material, a transmission, …
fn check_top_level(
    file: &str,
    line: usize,
    name: &str,
    element: &BytesStart<'_>,
    is_empty: bool,
    walk: &mut Walk,
) -> Result<(), UrdfError> {
    let own_name = attribute(element, "name");
    walk.owner = match &own_name {
        Some(own_name) => format!("{name} '{own_name}'"),
        None => name.to_string(),
    };
    let Some(own_name) = own_name else {
        if matches!(name, "link" | "joint") {
            // Reported at its end, after anything inside it (an element nested too deep).
            walk.nameless = Some((name.to_string(), line));
            if is_empty {
                return check_named(file, walk);
            }
        }
        return Ok(());
    };
    check_unique(file, line, name, &own_name, &mut walk.names)?;
    if name == "joint" {
        let kind = check_joint_type(file, line, &walk.owner, element)?;
        let joint = OpenJoint::new(own_name, kind, line);
        if is_empty {
            check_joint_end(file, &joint)?;
        } else {
            walk.open_joint = Some(joint);
        }
    }
    Ok(())
}

/// At the end of a top-level element: did it have the name it needs?
fn check_named(file: &str, walk: &mut Walk) -> Result<(), UrdfError> {
    match walk.nameless.take() {
        Some((tag, line)) => Err(at_line(
            file,
            line,
            format!("a <{tag}> has no name attribute"),
        )),
        None => Ok(()),
    }
}

/// At the end of the text: is every element closed, and was there a `<robot>`?
fn check_end(file: &str, walk: &Walk) -> Result<(), UrdfError> {
    match walk.open_elements.last() {
        None if walk.roots == 0 => Err(at_line(file, 1, "no <robot> element".to_string())),
        None => Ok(()),
        Some((name, line)) => Err(UrdfError::Xml {
            file: file.to_string(),
            line: *line,
            message: format!("<{name}> opened on this line is never closed (the text ends first)"),
        }),
    }
}

fn check_unique(
    file: &str,
    line: usize,
    element: &str,
    name: &str,
    seen: &mut NamesSeen,
) -> Result<(), UrdfError> {
    let (kind, first_lines) = match element {
        "link" => ("link", &mut seen.links),
        "joint" => ("joint", &mut seen.joints),
        _ => return Ok(()),
    };
    if let Some(&first_line) = first_lines.get(name) {
        return Err(UrdfError::Duplicate {
            file: file.to_string(),
            line,
            kind,
            name: name.to_string(),
            first_line,
        });
    }
    first_lines.insert(name.to_string(), line);
    Ok(())
}

/// Every numeric attribute of `element` holds the count of finite numbers it should.
fn check_numbers(
    file: &str,
    line: usize,
    owner: &str,
    name: &str,
    element: &BytesStart<'_>,
) -> Result<(), UrdfError> {
    for attr in element.attributes().flatten() {
        let key = String::from_utf8_lossy(attr.key.as_ref()).into_owned();
        let Some(arity) = numeric_arity(name, &key) else {
            continue;
        };
        let value = attr
            .unescape_value()
            .map(|v| v.into_owned())
            .unwrap_or_default();
        let mut count = 0;
        let all_finite = value.split_whitespace().all(|t| {
            count += 1;
            t.parse::<f64>().is_ok_and(f64::is_finite)
        });
        if count != arity || !all_finite {
            let expected = match arity {
                1 => "one finite number",
                3 => "3 finite numbers separated by spaces",
                _ => "4 finite numbers separated by spaces",
            };
            return Err(UrdfError::BadValue {
                file: file.to_string(),
                line,
                context: format!("{owner} <{name}>"),
                attribute: key,
                value: shorten(value),
                expected,
            });
        }
    }
    Ok(())
}

/// A value as quoted in a message: at most
/// [`MAX_QUOTED_CHARS`](fairgrasp_types::text::MAX_QUOTED_CHARS) characters and its length.
fn shorten(value: String) -> String {
    fairgrasp_types::text::excerpt(&value, fairgrasp_types::text::MAX_QUOTED_CHARS)
}

/// The joint's `type`, if it is a URDF joint type.
fn check_joint_type(
    file: &str,
    line: usize,
    owner: &str,
    element: &BytesStart<'_>,
) -> Result<JointKind, UrdfError> {
    let found = attribute(element, "type");
    found
        .as_deref()
        .and_then(JointKind::from_name)
        .ok_or_else(|| UrdfError::UnknownJointType {
            file: file.to_string(),
            line,
            joint: owner.to_string(),
            value: found.map_or_else(|| "(missing)".to_string(), shorten),
        })
}
