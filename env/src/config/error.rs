//! Why a configuration was refused.

/// A configuration value that is out of its allowed range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConfigError {
    #[error("{field} = {value}: {rule}")]
    Invalid {
        field: String,
        value: String,
        /// What the value must be, e.g. `must be in [0, 0.05] s`.
        rule: std::borrow::Cow<'static, str>,
    },
    #[error("{path}: {message}")]
    File { path: String, message: String },
}
