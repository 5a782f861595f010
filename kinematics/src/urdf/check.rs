//! A first pass over URDF text that names the offending element, attribute and line.
//!
//! This pass reads the XML once, in time linear in its length and with no recursion, before the
//! robot is read out of it (`read.rs`), and reports the first fault as
//! `line N: joint 'j2' <origin> xyz="0 0 abc": …`. It checks
//! - the size ([`MAX_URDF_BYTES`]) and the nesting depth ([`MAX_NESTING_DEPTH`]),
//! - every joint's type, and that revolute and prismatic joints have a `<limit>`,
//! - that no two links and no two joints share a name,
//! - every numeric attribute: the count of numbers, each of them finite.

use std::collections::HashMap;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::error::UrdfError;
use crate::urdf::joint::JointKind;

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

/// A top-level `<joint>` whose end has not been read yet.
struct OpenJoint {
    name: String,
    kind: JointKind,
    line: usize,
    has_limit: bool,
}

/// The first line each link name and each joint name was defined on.
#[derive(Default)]
struct NamesSeen {
    links: HashMap<String, usize>,
    joints: HashMap<String, usize>,
}

/// Checks size, nesting, joint types and limits, unique names and numeric attributes; `file` is
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
    let mut owner = String::from("robot");
    // The elements opened and not yet closed: name and line, outermost first.
    let mut open_elements: Vec<(String, usize)> = Vec::new();
    let mut names = NamesSeen::default();
    let mut open_joint: Option<OpenJoint> = None;
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
                open_elements.pop();
                if open_elements.len() == 1
                    && let Some(joint) = open_joint.take()
                {
                    check_limit_present(file, &joint)?;
                }
                continue;
            }
            Event::Eof => return check_all_closed(file, &open_elements),
            _ => continue,
        };
        let line = lines.line_at(start);
        let name = String::from_utf8_lossy(element.name().as_ref()).into_owned();
        let level = open_elements.len() + 1;
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
            open_elements.push((name.clone(), line));
        }
        if level == 2 {
            // A direct child of <robot>: a link, a joint, a material, a transmission, …
            let own_name = attribute(element, "name");
            owner = match &own_name {
                Some(own_name) => format!("{name} '{own_name}'"),
                None => name.clone(),
            };
            if let Some(own_name) = &own_name {
                check_unique(file, line, &name, own_name, &mut names)?;
            }
            if name == "joint" {
                let joint = OpenJoint {
                    name: own_name.unwrap_or_default(),
                    kind: check_joint_type(file, line, &owner, element)?,
                    line,
                    has_limit: false,
                };
                if is_empty {
                    check_limit_present(file, &joint)?;
                } else {
                    open_joint = Some(joint);
                }
            }
        } else if level == 3
            && name == "limit"
            && let Some(joint) = open_joint.as_mut()
        {
            joint.has_limit = true;
        }
        check_numbers(file, line, &owner, &name, element)?;
    }
}

/// At the end of the text: is every element closed?
fn check_all_closed(file: &str, open_elements: &[(String, usize)]) -> Result<(), UrdfError> {
    match open_elements.last() {
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

fn check_limit_present(file: &str, joint: &OpenJoint) -> Result<(), UrdfError> {
    if joint.kind.has_position_limits() && !joint.has_limit {
        return Err(UrdfError::MissingLimit {
            file: file.to_string(),
            line: joint.line,
            joint: joint.name.clone(),
            kind: joint.kind.name().to_string(),
        });
    }
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

/// Attribute `key` of `element`, unescaped (`None` when absent or not decodable).
pub(crate) fn attribute(element: &BytesStart<'_>, key: &str) -> Option<String> {
    element
        .attributes()
        .flatten()
        .find(|a| a.key.as_ref() == key.as_bytes())
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
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
