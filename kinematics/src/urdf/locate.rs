//! Where urdf-rs's fault is: urdf-rs says what it refused (`missing field `geometry``) but not
//! where, so the text it refused is read again piece by piece.
//!
//! Each top-level `<link>`, `<joint>` and `<material>` is read alone (wrapped in a `<robot>`);
//! in the first one urdf-rs refuses, each direct child is read alone inside a minimal element of
//! the same kind. The message names the child (`line 14: link 'palm' <visual>: …`), else the
//! element (`line 12: link 'palm': …`), else the `<robot>`. This runs only after a refusal, and
//! reads each element once and each child of one element once: time linear in the text.

use std::ops::Range;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

use crate::urdf::check::LineCounter;
use crate::urdf::check_joint::at_line;
use crate::urdf::error::UrdfError;
use crate::urdf::xml::attribute;

/// The longest part of urdf-rs's message quoted \[characters\] (it may quote a value whole).
const MAX_MESSAGE_CHARS: usize = 200;

/// One element of the text: its tag, its `name` attribute and where it is.
struct Piece {
    tag: String,
    name: Option<String>,
    /// Bytes of the text, from `<` to the end of its closing tag.
    span: Range<usize>,
}

/// The error for `text` (from `file`), which passed the pre-check and which urdf-rs refused
/// with `message`: the message, with the line and element it concerns.
pub(crate) fn locate(file: &str, text: &str, message: &str) -> UrdfError {
    if let Some((line, column, reason)) = xml_reader_position(message)
        && !has_bare_cr(text)
    {
        let reason = fairgrasp_types::text::excerpt(reason, MAX_MESSAGE_CHARS);
        let place = element_at(text, offset_of(text, line, column))
            .map(|owner| format!("{owner}: "))
            .unwrap_or_default();
        let message = format!("{place}urdf-rs's XML reader, column {column}: {reason}");
        return at_line(file, line, message);
    }
    let message = fairgrasp_types::text::excerpt(&plain(message), MAX_MESSAGE_CHARS);
    let mut lines = LineCounter::new(text);
    let Some(robot) = children(text, 0..text.len(), 1).into_iter().next() else {
        return at_line(file, 1, format!("urdf-rs: {message}"));
    };
    for element in children(text, robot.span.clone(), 2) {
        let Some(open) = opening(&element) else {
            continue;
        };
        let alone = format!("<robot>{}</robot>", &text[element.span.clone()]);
        if urdf_rs::read_from_string(&alone).is_ok() {
            continue;
        }
        let owner = element.owner();
        for part in children(text, element.span.clone(), 2) {
            if element.tag == "joint" && matches!(part.tag.as_str(), "parent" | "child") {
                continue; // the pre-check read them; the minimal joint has its own
            }
            let part_text = &text[part.span.clone()];
            let close = &element.tag;
            if urdf_rs::read_from_string(&format!("<robot>{open}{part_text}</{close}></robot>"))
                .is_err()
            {
                let line = lines.line_at(part.span.start);
                let tag = &part.tag;
                return at_line(file, line, format!("{owner} <{tag}>: urdf-rs: {message}"));
            }
        }
        let line = lines.line_at(element.span.start);
        return at_line(file, line, format!("{owner}: urdf-rs: {message}"));
    }
    let line = lines.line_at(robot.span.start);
    at_line(file, line, format!("<robot>: urdf-rs: {message}"))
}

/// The top-level element (`link 'palm'`) and its child (` <visual>`) that hold byte `offset`,
/// as the messages name them.
fn element_at(text: &str, offset: usize) -> Option<String> {
    let robot = children(text, 0..text.len(), 1).into_iter().next()?;
    let holds = |piece: &Piece| piece.span.contains(&offset);
    let element = children(text, robot.span, 2).into_iter().find(holds)?;
    let owner = element.owner();
    Some(
        match children(text, element.span, 2).into_iter().find(holds) {
            Some(part) => format!("{owner} <{}>", part.tag),
            None => owner,
        },
    )
}

/// The byte offset of `column` (characters from the line's start) of `line` (from 1, counting
/// LFs), or of the line's end if it is shorter.
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start = match line.checked_sub(2) {
        None => 0,
        Some(ends) => text
            .match_indices('\n')
            .nth(ends)
            .map_or(text.len(), |(i, _)| i + 1),
    };
    let rest = &text[start..];
    let line_end = rest.find('\n').unwrap_or(rest.len());
    start
        + rest[..line_end]
            .char_indices()
            .nth(column)
            .map_or(line_end, |(i, _)| i)
}

/// Line, column and reason of an error of urdf-rs's first XML reader (RustyXML), which reads
/// the text as given: `Parse error; Line: 12, Column: 5, Reason: …`.
fn xml_reader_position(message: &str) -> Option<(usize, usize, &str)> {
    let rest = message.strip_prefix("Parse error; Line: ")?;
    let (line, rest) = rest.split_once(", Column: ")?;
    let (column, reason) = rest.split_once(", Reason: ")?;
    Some((line.parse().ok()?, column.parse().ok()?, reason))
}

/// Does `text` end a line with a lone CR? (urdf-rs's XML reader then numbers lines wrongly:
/// it counts LFs.)
fn has_bare_cr(text: &str) -> bool {
    let bytes = text.as_bytes();
    bytes
        .iter()
        .enumerate()
        .any(|(i, &b)| b == b'\r' && bytes.get(i + 1) != Some(&b'\n'))
}

/// urdf-rs's `message` without what means nothing to the reader of the file: serde's `custom: `
/// and the position in urdf-rs's rewritten copy of the text (`Syntax: 32:40 `).
fn plain(message: &str) -> String {
    let message = message.strip_prefix("custom: ").unwrap_or(message);
    if let Some(rest) = message.strip_prefix("Syntax: ")
        && let Some((position, rest)) = rest.split_once(' ')
        && position.split(':').all(|n| n.parse::<usize>().is_ok())
    {
        return format!("XML syntax: {rest}");
    }
    message.to_string()
}

impl Piece {
    /// The element as messages name it: `link 'palm'`, or its tag alone.
    fn owner(&self) -> String {
        match &self.name {
            Some(name) => format!("{} '{name}'", self.tag),
            None => self.tag.clone(),
        }
    }
}

/// The minimal element of `element`'s kind that urdf-rs reads, open for one child; `None` for
/// elements urdf-rs skips.
fn opening(element: &Piece) -> Option<&'static str> {
    match element.tag.as_str() {
        "link" => Some("<link name=\"l\">"),
        "joint" => Some("<joint name=\"j\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/>"),
        "material" => Some("<material name=\"m\">"),
        _ => None,
    }
}

/// The elements at `child_level` of `span` of `text`, in order: with `span` an element and
/// `child_level` 2, its direct children (it is level 1); with `span` the whole text and
/// `child_level` 1, the root elements. Stops at the first XML error (the pre-check found none).
fn children(text: &str, span: Range<usize>, child_level: usize) -> Vec<Piece> {
    let inner = &text[span.clone()];
    let mut reader = Reader::from_str(inner);
    let mut depth = 0usize;
    let mut pieces = Vec::new();
    let mut open: Option<(String, Option<String>, usize)> = None;
    loop {
        let start = reader.buffer_position() as usize;
        let event = match reader.read_event() {
            Ok(Event::Eof) | Err(_) => return pieces,
            Ok(event) => event,
        };
        let end = span.start + reader.buffer_position() as usize;
        match &event {
            Event::Start(e) => {
                depth += 1;
                if depth == child_level {
                    open = Some(named(e, span.start + start));
                }
            }
            Event::Empty(e) if depth + 1 == child_level => {
                let (tag, name, from) = named(e, span.start + start);
                pieces.push(Piece {
                    tag,
                    name,
                    span: from..end,
                });
            }
            Event::End(_) => {
                if depth == child_level
                    && let Some((tag, name, from)) = open.take()
                {
                    pieces.push(Piece {
                        tag,
                        name,
                        span: from..end,
                    });
                }
                depth = depth.saturating_sub(1);
            }
            _ => {}
        }
    }
}

/// `element`'s tag and `name` attribute, and its start `offset`.
fn named(element: &BytesStart<'_>, offset: usize) -> (String, Option<String>, usize) {
    let tag = String::from_utf8_lossy(element.name().as_ref()).into_owned();
    (tag, attribute(element, "name"), offset)
}
