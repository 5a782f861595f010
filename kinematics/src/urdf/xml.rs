//! What the pre-check (`check.rs`, `check_joint.rs`) and the line finder (`locate.rs`) read of
//! one XML element, in one place, so neither imports the other for it.

use quick_xml::events::BytesStart;

/// Attribute `key` of `element`, unescaped (`None` when absent or not decodable).
pub(crate) fn attribute(element: &BytesStart<'_>, key: &str) -> Option<String> {
    element
        .attributes()
        .flatten()
        .find(|a| a.key.as_ref() == key.as_bytes())
        .and_then(|a| a.unescape_value().ok().map(|v| v.into_owned()))
}
