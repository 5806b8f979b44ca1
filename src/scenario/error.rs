//! What is wrong with a scenario: every error names the key, the value and what is allowed.

use std::fmt;

/// A scenario that failed to read or validate. Every variant names what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum ScenarioError {
    /// The file could not be read.
    Io { path: String, message: String },
    /// The text is not TOML.
    Syntax(String),
    /// A key with a value that is not allowed.
    Invalid {
        key: String,
        value: String,
        allowed: String,
    },
    /// A key that the scenario does not have.
    UnknownKey {
        key: String,
        hint: String,
        known: String,
    },
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ScenarioError::Io { path, message } => {
                write!(f, "cannot read scenario file {path}: {message}")
            }
            ScenarioError::Syntax(m) => write!(f, "scenario is not valid TOML: {m}"),
            ScenarioError::Invalid {
                key,
                value,
                allowed,
            } => write!(
                f,
                "scenario key `{key}` = {value} is not allowed: expected {allowed}"
            ),
            ScenarioError::UnknownKey { key, hint, known } => write!(
                f,
                "scenario key `{key}` is unknown{hint}; this table knows: {known}"
            ),
        }
    }
}

impl std::error::Error for ScenarioError {}
