//! A shape model read by its content: a vertex-facet plate model (plate.rs) when the first
//! line that is not blank holds one or two numbers and nothing else (the counts `NV NF` or
//! `NV`; the plate reader refuses numbers that are no counts, `-5 320`, as a plate model's
//! header), a Wavefront OBJ file (obj.rs) otherwise. No OBJ file starts so (its lines
//! start with a keyword), so an OBJ file is read as [`read_obj`](super::read_obj) reads it, with the same
//! mesh or the same message, except that a UTF-8 byte order mark at its very start is read
//! past here (for either format) and refused there.

use super::error::ShapeError;
use super::mesh::Mesh;
use super::obj::{self, MAX_LINE_BYTES};
use super::plate::{self, is_count};
use std::io::{BufRead, BufReader, Cursor, Read};
use std::path::Path;

/// Reads the shape model at `path`, plate or OBJ by its content, its coordinates multiplied
/// by `metres_per_unit`. The mesh is not yet checked: see [`Mesh::check`].
pub fn read_shape(path: &Path, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    let (file, name) = super::error::open(path)?;
    read(file, &name, metres_per_unit)
}

/// Parses the text of a shape model named `name` (in messages), plate or OBJ by its
/// content, its coordinates multiplied by `metres_per_unit`. The mesh is not yet checked.
pub fn parse_shape(text: &str, name: &str, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    read(text.as_bytes(), name, metres_per_unit)
}

/// The UTF-8 byte order mark.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Whether a line holds one or two numbers and nothing else: a plate model's counts, or
/// what was meant as them (an OBJ line starts with a keyword).
fn is_plate_counts(line: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(line) else {
        return false;
    };
    let mut n = 0;
    for word in text.split_whitespace() {
        n += 1;
        if n > 2 || !(is_count(word) || word.parse::<f64>().is_ok()) {
            return false;
        }
    }
    n > 0
}

/// Reads up to the first line that is not blank, chooses the format by it, and gives the
/// chosen reader the file as it was: the blank lines as empty ones (both readers skip them,
/// and the line numbers stay), then the line itself and the rest, untouched.
fn read<R: BufRead>(mut reader: R, name: &str, scale: f64) -> Result<Mesh, ShapeError> {
    if !(scale.is_finite() && scale > 0.0) {
        // The OBJ reader's message, before anything is read (as read_obj gives it).
        return obj::parse(&b""[..], name, scale);
    }
    // A UTF-8 byte order mark, as some Windows tools write one, is no part of either format.
    let head = reader.fill_buf().map_err(|e| ShapeError::Read {
        file: name.to_string(),
        reason: e.to_string(),
    })?;
    if head.starts_with(BOM) {
        reader.consume(BOM.len());
    }
    let mut blank = 0u64;
    let mut first = Vec::new();
    let is_plate = loop {
        first.clear();
        let read = (&mut reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut first)
            .map_err(|e| ShapeError::Read {
                file: name.to_string(),
                reason: e.to_string(),
            })?;
        if read == 0 {
            break false;
        }
        // A line too long for either reader goes to the OBJ reader, which refuses it.
        let too_long = first.len() > MAX_LINE_BYTES && first.last() != Some(&b'\n');
        if too_long {
            break false;
        }
        if !first.iter().all(u8::is_ascii_whitespace) {
            break is_plate_counts(&first);
        }
        blank += 1;
    };
    let replayed = BufReader::new(
        std::io::repeat(b'\n')
            .take(blank)
            .chain(Cursor::new(first))
            .chain(reader),
    );
    if is_plate {
        plate::parse(replayed, name, scale)
    } else {
        obj::parse(replayed, name, scale)
    }
}

#[cfg(test)]
mod tests {
    use super::parse_shape;

    #[test]
    fn a_byte_order_mark_is_read_past_in_either_format() {
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
        let plate = "4 4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n\
                     1 1 3 2\n2 1 2 4\n3 1 4 3\n4 2 3 4\n";
        for text in [obj, plate] {
            let plain = parse_shape(text, "t", 1.0).expect("reads");
            let marked =
                parse_shape(&format!("\u{feff}{text}"), "t", 1.0).expect("reads with a BOM");
            assert_eq!(plain.vertices, marked.vertices);
            assert_eq!(plain.facets, marked.facets);
        }
        // Only at the start: elsewhere it is content, refused as before.
        assert!(parse_shape(&format!("{obj}\u{feff}v 0 0 0\n"), "t", 1.0).is_err());
    }
}
