//! What is wrong with a scenario: every error names the key, the value and what is allowed.

use std::fmt;

/// A scenario that failed to read or validate. Every variant names what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum ScenarioError {
    /// The file could not be read.
    Io {
        /// The file as given.
        path: String,
        /// What the system said.
        message: String,
    },
    /// The text is not TOML.
    Syntax(String),
    /// A key with a value that is not allowed.
    Invalid {
        /// The dotted key (`lander.mass_kg`).
        key: String,
        /// The value found, as the file writes it.
        value: String,
        /// What the key allows, and why.
        allowed: String,
    },
    /// A key that the scenario does not have.
    UnknownKey {
        /// The dotted key.
        key: String,
        /// `; did you mean ...?` with the closest known key, or empty.
        hint: String,
        /// The keys the table knows, listed.
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
