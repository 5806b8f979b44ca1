//! A shape model read by its content: a vertex-facet plate model (plate.rs) when the first
//! line that is not blank holds one or two numbers and nothing else (the counts `NV NF` or
//! `NV`; the plate reader refuses numbers that are no counts, `-5 320`, as a plate model's
//! header), a Wavefront OBJ file (obj.rs) otherwise. A first line of one count (digits only)
//! is a plate model's `NV` or an ICQ model's grid size `Q` (icq.rs): the next line that is
//! not blank tells them apart, an ICQ model when it holds exactly three numbers (a row
//! `x y z`, Fortran's `1.5D-3` a number too), a plate model otherwise (its rows `i x y z`
//! hold four; a file of `NV` and a first row of three numbers, a plate model's refused
//! either way, is refused as an ICQ model). No OBJ file starts so (its lines start with a
//! keyword), so an OBJ file is read as [`read_obj`](super::read_obj) reads it, a plate file
//! as [`read_plate`](super::read_plate) and an ICQ file as [`read_icq`](super::read_icq),
//! with the same mesh or the same message, except that a UTF-8 byte order mark at its very
//! start is read past here (for any format) and refused there. The lines read to choose are
//! given back to the chosen reader, so its messages number the lines as in the file.

use super::error::ShapeError;
use super::icq;
use super::mesh::Mesh;
use super::obj::{self, MAX_LINE_BYTES};
use super::plate::{self, is_count};
use std::io::{BufRead, BufReader, Cursor, Read};
use std::path::Path;

/// Reads the shape model at `path`, plate, ICQ or OBJ by its content, its coordinates multiplied
/// by `metres_per_unit`. The mesh is not yet checked: see [`Mesh::check`].
pub fn read_shape(path: &Path, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    let (file, name) = super::error::open(path)?;
    read(file, &name, metres_per_unit)
}

/// Parses the text of a shape model named `name` (in messages), plate, ICQ or OBJ by its
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

/// Whether a line holds one count (digits only) and nothing else: a plate model's `NV` or
/// an ICQ model's `Q`.
fn is_one_count(line: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(line) else {
        return false;
    };
    let mut words = text.split_whitespace();
    matches!((words.next(), words.next()), (Some(word), None) if is_count(word))
}

/// Whether a line holds exactly three numbers: an ICQ model's row `x y z`.
fn is_three_numbers(line: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(line) else {
        return false;
    };
    let mut n = 0;
    for word in text.split_whitespace() {
        n += 1;
        if n > 3 || icq::number(word).is_none() {
            return false;
        }
    }
    n == 3
}

/// The format a file is read in.
#[derive(Clone, Copy, PartialEq)]
enum Format {
    Obj,
    Plate,
    Icq,
}

/// Reads the next line of `reader` into `line` (cleared first), at most one byte more than
/// [`MAX_LINE_BYTES`]: the bytes read, 0 at the end of the file.
fn next_line<R: BufRead>(
    reader: &mut R,
    line: &mut Vec<u8>,
    name: &str,
) -> Result<usize, ShapeError> {
    line.clear();
    reader
        .take(MAX_LINE_BYTES as u64 + 1)
        .read_until(b'\n', line)
        .map_err(|e| ShapeError::Read {
            file: name.to_string(),
            reason: e.to_string(),
        })
}

/// Whether a line read by [`next_line`] is longer than [`MAX_LINE_BYTES`].
fn too_long(line: &[u8]) -> bool {
    line.len() > MAX_LINE_BYTES && line.last() != Some(&b'\n')
}

/// Reads up to the first line that is not blank, chooses the format by it (and, after one
/// count, by the next line that is not blank), and gives the chosen reader the file as it
/// was: the blank lines as empty ones (every reader skips them, and the line numbers stay),
/// then the lines read and the rest, untouched.
fn read<R: BufRead>(mut reader: R, name: &str, scale: f64) -> Result<Mesh, ShapeError> {
    if !(scale.is_finite() && scale > 0.0) {
        // The OBJ reader's message, before anything is read (as read_obj gives it).
        return obj::parse(&b""[..], name, scale);
    }
    // A UTF-8 byte order mark, as some Windows tools write one, is no part of any format.
    let head = reader.fill_buf().map_err(|e| ShapeError::Read {
        file: name.to_string(),
        reason: e.to_string(),
    })?;
    if head.starts_with(BOM) {
        reader.consume(BOM.len());
    }
    let mut blank = 0u64;
    let mut first = Vec::new();
    let mut format = loop {
        // A line too long for any reader goes to the OBJ reader, which refuses it.
        if next_line(&mut reader, &mut first, name)? == 0 || too_long(&first) {
            break Format::Obj;
        }
        if !first.iter().all(u8::is_ascii_whitespace) {
            break if is_plate_counts(&first) {
                Format::Plate
            } else {
                Format::Obj
            };
        }
        blank += 1;
    };
    // One count: `NV` of a plate model or `Q` of an ICQ model, told apart by the next line
    // (one too long, or none, is the plate reader's to refuse, as before).
    let mut between = 0u64;
    let mut second = Vec::new();
    if format == Format::Plate && is_one_count(&first) {
        format = loop {
            if next_line(&mut reader, &mut second, name)? == 0 || too_long(&second) {
                break Format::Plate;
            }
            if !second.iter().all(u8::is_ascii_whitespace) {
                break if is_three_numbers(&second) {
                    Format::Icq
                } else {
                    Format::Plate
                };
            }
            between += 1;
        };
    }
    let replayed = BufReader::new(
        std::io::repeat(b'\n')
            .take(blank)
            .chain(Cursor::new(first))
            .chain(std::io::repeat(b'\n').take(between))
            .chain(Cursor::new(second))
            .chain(reader),
    );
    match format {
        Format::Plate => plate::parse(replayed, name, scale),
        Format::Icq => icq::parse(replayed, name, scale),
        Format::Obj => obj::parse(replayed, name, scale),
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
