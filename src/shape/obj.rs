//! Wavefront OBJ shape models, read line by line into a [`Mesh`] in metres.
//!
//! Read: `v x y z` (a fourth number, OBJ's weight `w` of rational curves, is accepted and
//! ignored: it does not move a polygon's vertex; so are MeshLab's colours, `v x y z r g b`)
//! and `f a b c ...` (also `a/t/n`, `a//n`, `a/t`: the texture and normal numbers are
//! ignored; negative numbers count back from the last vertex read; a polygon of more than
//! three vertices is split into the fan `a b c`, `a c d`, ...). `#` starts a comment.
//! Ignored, because they do not change the body's shape: `vn`, `vt`, `vp`, `o`, `g`, `s`,
//! `usemtl`, `mtllib`. Any other statement (`l`, `p`, curves, surfaces...) is refused: a
//! shape read without it might not be the shape the file meant.
//!
//! A facet may name only vertices defined on the lines before it (as every shape model
//! does), so each line is checked as it is read and the error names it. A hostile file
//! cannot make the reader allocate without bound: lines longer than [`MAX_LINE_BYTES`], more
//! than [`MAX_VERTICES`] vertices or more than [`MAX_FACETS`] triangles are refused.

use super::error::ShapeError;
use super::mesh::{MAX_FACETS, MAX_VERTICES, Mesh};
use std::io::{BufRead, Read};
use std::path::Path;

/// The longest line read, in bytes.
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Reads the OBJ shape model at `path`, its coordinates multiplied by `metres_per_unit`
/// (1000 for a model in kilometres, as PDS shape models usually are). The mesh is not yet
/// checked: see [`Mesh::check`].
pub fn read_obj(path: &Path, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    let (file, name) = super::error::open(path)?;
    parse(file, &name, metres_per_unit)
}

/// Parses the text of an OBJ shape model named `name` (in messages), its coordinates
/// multiplied by `metres_per_unit`. The mesh is not yet checked: see [`Mesh::check`].
pub fn parse_obj(text: &str, name: &str, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    parse(text.as_bytes(), name, metres_per_unit)
}

pub(super) fn parse<R: BufRead>(mut reader: R, name: &str, scale: f64) -> Result<Mesh, ShapeError> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(ShapeError::Value(format!(
            "metres per unit of the shape model {name} must be a positive number, not {scale}"
        )));
    }
    let mut mesh = Mesh::default();
    let mut buf = Vec::new();
    let mut line = 0;
    loop {
        buf.clear();
        let read = (&mut reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut buf)
            .map_err(|e| ShapeError::Read {
                file: name.to_string(),
                reason: e.to_string(),
            })?;
        if read == 0 {
            return Ok(mesh);
        }
        line += 1;
        let at = |reason: String| ShapeError::Line {
            file: name.to_string(),
            line,
            reason,
        };
        if buf.len() > MAX_LINE_BYTES && buf.last() != Some(&b'\n') {
            return Err(at(format!("longer than {MAX_LINE_BYTES} bytes")));
        }
        let text = std::str::from_utf8(&buf).map_err(|_| at("not text (UTF-8)".into()))?;
        statement(text, &mut mesh, scale).map_err(at)?;
    }
}

/// Reads one line into `mesh`, or says what is wrong with it.
fn statement(text: &str, mesh: &mut Mesh, scale: f64) -> Result<(), String> {
    let code = text.split('#').next().unwrap_or("");
    let mut words = code.split_whitespace();
    let Some(keyword) = words.next() else {
        return Ok(());
    };
    match keyword {
        "v" => vertex(words, mesh, scale),
        "f" => facet(words, mesh),
        "vn" | "vt" | "vp" | "o" | "g" | "s" | "usemtl" | "mtllib" => Ok(()),
        other => Err(format!(
            "unknown statement {} (a shape model is read from its v and f lines; vn, vt, vp, \
             o, g, s, usemtl and mtllib are ignored)",
            quoted(other)
        )),
    }
}

/// A word of the file for a message: quoted, escaped, at most 24 characters.
fn quoted(word: &str) -> String {
    let short: String = word.chars().take(24).collect();
    let more = if short.len() < word.len() { "..." } else { "" };
    format!("'{}{more}'", short.escape_debug())
}

fn vertex<'a>(
    words: impl Iterator<Item = &'a str>,
    mesh: &mut Mesh,
    scale: f64,
) -> Result<(), String> {
    let mut xyz = [0.0; 3];
    let mut count = 0;
    for word in words {
        let value: f64 = word
            .parse()
            .map_err(|_| format!("{} is not a number", quoted(word)))?;
        if !value.is_finite() {
            return Err(format!("{} is not a finite number", quoted(word)));
        }
        if count < 3 {
            xyz[count] = value * scale;
            if !xyz[count].is_finite() {
                return Err(format!("{} overflows in metres", quoted(word)));
            }
        }
        count += 1;
        if count > 7 {
            break;
        }
    }
    if !matches!(count, 3 | 4 | 6) {
        return Err(format!(
            "a vertex has 3 coordinates (x y z, optionally a weight w, or colours r g b), \
             not {}",
            if count > 7 {
                "more than 7".into()
            } else {
                count.to_string()
            }
        ));
    }
    if mesh.vertices.len() >= MAX_VERTICES {
        return Err(format!(
            "more than {MAX_VERTICES} vertices: touchdown reads shape models of at most \
             {MAX_VERTICES} vertices"
        ));
    }
    mesh.vertices.push(xyz);
    Ok(())
}

/// The 0-based vertex a facet's word names (`a`, `a/t`, `a//n`, `a/t/n`, negative = relative).
fn vertex_number(word: &str, defined: usize) -> Result<u32, String> {
    let first = word.split('/').next().unwrap_or("");
    let k: i64 = first
        .parse()
        .map_err(|_| format!("{} is not a vertex number", quoted(word)))?;
    let index = if k > 0 {
        if k as u64 > defined as u64 {
            return Err(format!(
                "vertex {k} is not defined ({defined} vertices before this line)"
            ));
        }
        k as u64 - 1
    } else if k < 0 {
        if k.unsigned_abs() > defined as u64 {
            return Err(format!(
                "relative vertex {k} reaches before the first vertex ({defined} vertices \
                 before this line)"
            ));
        }
        defined as u64 - k.unsigned_abs()
    } else {
        return Err("vertex number 0: OBJ numbers vertices from 1".into());
    };
    // `defined` is at most MAX_VERTICES, far below u32::MAX.
    u32::try_from(index).map_err(|_| format!("vertex {k} is out of range"))
}

fn facet<'a>(words: impl Iterator<Item = &'a str>, mesh: &mut Mesh) -> Result<(), String> {
    let defined = mesh.vertices.len();
    let mut first = 0;
    let mut previous = 0;
    let mut count = 0usize;
    for word in words {
        let v = vertex_number(word, defined)?;
        match count {
            0 => first = v,
            1 => {}
            _ => {
                if mesh.facets.len() >= MAX_FACETS {
                    return Err(format!(
                        "more than {MAX_FACETS} facets: touchdown reads shape models of at \
                         most {MAX_FACETS} triangles"
                    ));
                }
                mesh.facets.push([first, previous, v]);
            }
        }
        previous = v;
        count += 1;
    }
    if count < 3 {
        return Err(format!("a facet needs at least 3 vertices, not {count}"));
    }
    Ok(())
}
