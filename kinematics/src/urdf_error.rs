//! Everything that can be wrong with a URDF, each naming the file and the culprit.

/// Why a URDF could not be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UrdfError {
    /// The file could not be read.
    #[error("{file}: cannot read: {message}")]
    Read { file: String, message: String },
    /// The text is not well-formed XML.
    #[error("{file}: line {line}: not well-formed XML: {message}")]
    Xml {
        file: String,
        line: usize,
        message: String,
    },
    /// A joint's `type` is not a URDF joint type.
    #[error(
        "{file}: line {line}: {joint} has type \"{value}\"; a URDF joint type is one of revolute, continuous, prismatic, fixed, floating, planar, spherical"
    )]
    UnknownJointType {
        file: String,
        line: usize,
        joint: String,
        value: String,
    },
    /// A numeric attribute does not hold the numbers it should.
    #[error("{file}: line {line}: {context} {attribute}=\"{value}\": expected {expected}")]
    BadValue {
        file: String,
        line: usize,
        context: String,
        attribute: String,
        value: String,
        expected: &'static str,
    },
    /// Anything else urdf-rs refused.
    #[error("{file}: not a valid URDF: {message}")]
    Parse { file: String, message: String },
    /// A joint names a link that does not exist.
    #[error("{file}: joint '{joint}' names {role} link '{link}', which is not defined")]
    MissingLink {
        file: String,
        joint: String,
        role: &'static str,
        link: String,
    },
    /// The links and joints do not form one tree.
    #[error("{file}: not a tree: {detail}")]
    NotATree { file: String, detail: String },
    /// A chain was asked for without a tip, and the tree branches.
    #[error(
        "{file}: not a serial chain: link '{link}' has {} child joints ({}); name a tip link to pick one branch",
        children.len(), children.join(", ")
    )]
    NonSerial {
        file: String,
        link: String,
        children: Vec<String>,
    },
    /// The tip link asked for does not exist.
    #[error("{file}: no link named '{link}' (links: {})", known.join(", "))]
    UnknownLink {
        file: String,
        link: String,
        known: Vec<String>,
    },
    /// The chain holds a joint fairgrasp cannot move along one axis.
    #[error(
        "{file}: joint '{joint}' is {kind}; a serial chain supports revolute, continuous, prismatic and fixed joints"
    )]
    UnsupportedJoint {
        file: String,
        joint: String,
        kind: String,
    },
    /// A joint's limits are inverted or its axis is zero.
    #[error("{file}: joint '{joint}': {problem}")]
    BadJoint {
        file: String,
        joint: String,
        problem: String,
    },
}
