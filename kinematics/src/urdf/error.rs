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
    /// The text is larger than fairgrasp reads.
    #[error(
        "{file}: {bytes} bytes is more than the {limit} bytes fairgrasp reads as a URDF (a URDF names its meshes, it does not hold them)"
    )]
    TooLarge {
        file: String,
        /// Size of the file or text \[bytes\].
        bytes: u64,
        /// [`crate::urdf::MAX_URDF_BYTES`] \[bytes\].
        limit: u64,
    },
    /// Elements nest deeper than any URDF does.
    #[error(
        "{file}: line {line}: element nesting depth {depth} at <{element}> exceeds the limit of {limit} levels (a URDF needs about 6)"
    )]
    TooDeep {
        file: String,
        line: usize,
        /// The element that went over the limit.
        element: String,
        /// Its depth, `<robot>` being 1.
        depth: usize,
        /// [`crate::urdf::MAX_NESTING_DEPTH`].
        limit: usize,
    },
    /// Two links or two joints share a name.
    #[error(
        "{file}: line {line}: a second {kind} named '{name}' (the first is on line {first_line}); {kind} names must be unique"
    )]
    Duplicate {
        file: String,
        line: usize,
        /// "link" or "joint".
        kind: &'static str,
        name: String,
        first_line: usize,
    },
    /// A revolute or prismatic joint without `<limit>`.
    #[error(
        "{file}: line {line}: joint '{joint}' is {kind} but has no <limit>; URDF requires <limit lower=\"…\" upper=\"…\" effort=\"…\" velocity=\"…\"/> for revolute and prismatic joints (use type=\"continuous\" for a joint without position limits)"
    )]
    MissingLimit {
        file: String,
        line: usize,
        joint: String,
        /// "revolute" or "prismatic".
        kind: String,
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
    /// The XML is well formed but not a URDF fairgrasp reads (no `<robot>`, a joint without
    /// its parent link, an element given twice, …); the message names the line.
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
