//! What can be wrong with a shape model: its file, a line of it, its mesh, or a value the
//! gravity is asked to use.

use std::fmt;

/// A shape model refused, with the file, the line or the edge that is wrong and what is
/// wrong with it. Vertex numbers are 1-based as in the file; facet numbers are 1-based in
/// file order, counting triangles (a polygon split into a fan counts as its triangles).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ShapeError {
    /// The file could not be read.
    Read {
        /// The file, as named by the caller.
        file: String,
        /// The operating system's reason.
        reason: String,
    },
    /// A line of the file is wrong.
    Line {
        /// The file, as named by the caller.
        file: String,
        /// The line, 1-based.
        line: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// The mesh is not a closed, consistently oriented, outward-facing surface of
    /// non-degenerate triangles (the message names the first bad edge or facet).
    Mesh(String),
    /// A value given to the gravity (density, spin axis) cannot be used.
    Value(String),
}

impl fmt::Display for ShapeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShapeError::Read { file, reason } => write!(f, "cannot read {file}: {reason}"),
            ShapeError::Line { file, line, reason } => write!(f, "{file}, line {line}: {reason}"),
            ShapeError::Mesh(m) => write!(f, "shape model refused: {m}"),
            ShapeError::Value(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for ShapeError {}

/// Opens the shape model at `path` for reading, with its name for messages.
pub(super) fn open(
    path: &std::path::Path,
) -> Result<(std::io::BufReader<std::fs::File>, String), ShapeError> {
    let name = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|e| ShapeError::Read {
        file: name.clone(),
        reason: e.to_string(),
    })?;
    Ok((std::io::BufReader::new(file), name))
}
