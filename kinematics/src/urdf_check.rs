//! A first pass over URDF text that names the offending element, attribute and line.
//!
//! `urdf-rs` reports a bad number or an unknown joint type without saying where; this pass reads
//! the XML once, checks every joint type and every numeric attribute, and reports the first fault
//! as `line N, joint 'j2' <origin xyz="0 0 abc">: …`.

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::UrdfError;

/// The joint types URDF defines (`urdf-rs` reads all of them).
pub const URDF_JOINT_TYPES: [&str; 7] = [
    "revolute",
    "continuous",
    "prismatic",
    "fixed",
    "floating",
    "planar",
    "spherical",
];

/// How many numbers an attribute holds, by element and attribute name.
fn numeric_arity(element: &str, attribute: &str) -> Option<usize> {
    match (element, attribute) {
        ("origin", "xyz" | "rpy") | ("axis", "xyz") | ("box", "size") | ("mesh", "scale") => {
            Some(3)
        }
        ("color", "rgba") => Some(4),
        ("limit", "lower" | "upper" | "effort" | "velocity")
        | ("mass", "value")
        | ("inertia", "ixx" | "ixy" | "ixz" | "iyy" | "iyz" | "izz")
        | ("cylinder" | "capsule", "radius" | "length")
        | ("sphere", "radius")
        | ("mimic", "multiplier" | "offset")
        | ("dynamics", "damping" | "friction")
        | ("safety_controller", _) => Some(1),
        _ => None,
    }
}

fn line_of(text: &str, byte: usize) -> usize {
    1 + text.as_bytes()[..byte.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// Checks joint types and numeric attributes; `file` is only used in messages.
pub fn check_urdf_text(file: &str, text: &str) -> Result<(), UrdfError> {
    let mut reader = Reader::from_str(text);
    let mut owner = String::from("robot");
    loop {
        let start = reader.buffer_position() as usize;
        let event = reader.read_event().map_err(|e| UrdfError::Xml {
            file: file.to_string(),
            line: line_of(text, reader.error_position() as usize),
            message: e.to_string(),
        })?;
        let element = match &event {
            Event::Start(e) | Event::Empty(e) => e.clone(),
            Event::Eof => return Ok(()),
            _ => continue,
        };
        let line = line_of(text, start);
        let name = String::from_utf8_lossy(element.name().as_ref()).into_owned();
        if name == "link" || name == "joint" {
            owner = format!(
                "{name} '{}'",
                attribute(&element, "name").unwrap_or_default()
            );
        }
        if name == "joint" {
            check_joint_type(file, line, &owner, &element)?;
        }
        for attr in element.attributes().flatten() {
            let key = String::from_utf8_lossy(attr.key.as_ref()).into_owned();
            let Some(arity) = numeric_arity(&name, &key) else {
                continue;
            };
            let value = attr
                .unescape_value()
                .map(|v| v.into_owned())
                .unwrap_or_default();
            let numbers: Vec<Option<f64>> = value
                .split_whitespace()
                .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
                .collect();
            if numbers.len() != arity || numbers.iter().any(Option::is_none) {
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
                    value,
                    expected,
                });
            }
        }
    }
}

fn attribute(element: &BytesStart<'_>, key: &str) -> Option<String> {
    element
        .attributes()
        .flatten()
        .find(|a| a.key.as_ref() == key.as_bytes())
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
}

fn check_joint_type(
    file: &str,
    line: usize,
    owner: &str,
    element: &BytesStart<'_>,
) -> Result<(), UrdfError> {
    match attribute(element, "type") {
        Some(kind) if URDF_JOINT_TYPES.contains(&kind.as_str()) => Ok(()),
        found => Err(UrdfError::UnknownJointType {
            file: file.to_string(),
            line,
            joint: owner.to_string(),
            value: found.unwrap_or_else(|| "(missing)".to_string()),
        }),
    }
}
