//! Vertex-facet "plate" shape models, read line by line into a [`Mesh`] in metres: the
//! form of the Gaskell (SPC) models in NASA's Planetary Data System (`verNNNq.tab`) and of
//! the Small Body Mapping Tool's `.plt` files.
//!
//! Two variants, whitespace-separated numbers, blank lines ignored:
//! - counts first, `NV NF` on one line (PDS `.tab`), then `NV` rows `i x y z` and `NF` rows
//!   `j a b c`;
//! - `NV` alone on the first line (SBMT `.plt`), the `NV` rows `i x y z`, a line `NF`, then
//!   the `NF` rows `j a b c`.
//!
//! Row `i` is the `i`-th vertex, numbered from 1 in file order, its coordinates in the file's
//! units; row `j` is the `j`-th facet, `a b c` its 1-based vertices counter-clockwise seen
//! from outside. Every row has exactly four numbers and its number is checked against its
//! place; a vertex number must lie in `1..=NV`; rows missing before the end of the file, and
//! anything but blank lines after the last facet, are refused. Errors name the file and the
//! line. The counts are checked against [`MAX_VERTICES`] and [`MAX_FACETS`] (and against 4,
//! the fewest a closed surface has) before anything is reserved, and the reader reserves at
//! most 65,536 rows ahead of those it has read (a header claiming the limits costs little);
//! lines are at most [`MAX_LINE_BYTES`] bytes.

use super::error::ShapeError;
use super::mesh::{MAX_FACETS, MAX_VERTICES, Mesh};
use super::obj::MAX_LINE_BYTES;
use std::io::{BufRead, Read};
use std::path::Path;

/// The most rows reserved ahead of reading them.
const RESERVE_AHEAD: usize = 1 << 16;

/// Reads the plate shape model at `path`, its coordinates multiplied by `metres_per_unit`
/// (1000 for a model in kilometres, as PDS models are). The mesh is not yet checked: see
/// [`Mesh::check`].
pub fn read_plate(path: &Path, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    let (file, name) = super::error::open(path)?;
    parse(file, &name, metres_per_unit)
}

/// Parses the text of a plate shape model named `name` (in messages), its coordinates
/// multiplied by `metres_per_unit`. The mesh is not yet checked: see [`Mesh::check`].
pub fn parse_plate(text: &str, name: &str, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    parse(text.as_bytes(), name, metres_per_unit)
}

/// A file's non-blank lines as text, numbered from 1 (blank lines counted), each at most
/// [`MAX_LINE_BYTES`] bytes (also the ICQ reader's, icq.rs).
pub(super) struct Lines<'n, R> {
    reader: R,
    name: &'n str,
    buf: Vec<u8>,
    /// The number of the last line read.
    pub(super) line: usize,
}

impl<'n, R: BufRead> Lines<'n, R> {
    /// The lines of `reader`, its file named `name` in messages.
    pub(super) fn new(reader: R, name: &'n str) -> Self {
        Lines {
            reader,
            name,
            buf: Vec::new(),
            line: 0,
        }
    }

    /// The error of line `line`: the file, the line and `reason`.
    pub(super) fn error(&self, line: usize, reason: String) -> ShapeError {
        ShapeError::Line {
            file: self.name.to_string(),
            line,
            reason,
        }
    }

    /// The next line that is not blank and its number, or `None` at the end of the file.
    pub(super) fn next(&mut self) -> Result<Option<(usize, &str)>, ShapeError> {
        loop {
            self.buf.clear();
            let read = (&mut self.reader)
                .take(MAX_LINE_BYTES as u64 + 1)
                .read_until(b'\n', &mut self.buf)
                .map_err(|e| ShapeError::Read {
                    file: self.name.to_string(),
                    reason: e.to_string(),
                })?;
            if read == 0 {
                return Ok(None);
            }
            self.line += 1;
            if self.buf.len() > MAX_LINE_BYTES && self.buf.last() != Some(&b'\n') {
                return Err(self.error(self.line, format!("longer than {MAX_LINE_BYTES} bytes")));
            }
            match std::str::from_utf8(&self.buf) {
                Ok(text) if text.split_whitespace().next().is_none() => {}
                Ok(_) => break,
                Err(_) => return Err(self.error(self.line, "not text (UTF-8)".into())),
            }
        }
        let text = std::str::from_utf8(&self.buf)
            .map_err(|_| self.error(self.line, "not text (UTF-8)".into()))?;
        Ok(Some((self.line, text)))
    }
}

/// A word of the file for a message: quoted, escaped, at most 24 characters.
pub(super) fn quoted(word: &str) -> String {
    let short: String = word.chars().take(24).collect();
    let more = if short.len() < word.len() { "..." } else { "" };
    format!("'{}{more}'", short.escape_debug())
}

/// A line's words: the first four, and how many there are.
fn words(text: &str) -> ([&str; 4], usize) {
    let mut first = [""; 4];
    let mut count = 0;
    for word in text.split_whitespace() {
        if let Some(slot) = first.get_mut(count) {
            *slot = word;
        }
        count += 1;
    }
    (first, count)
}

/// Whether a word is a count: decimal digits only.
pub(super) fn is_count(word: &str) -> bool {
    !word.is_empty() && word.bytes().all(|b| b.is_ascii_digit())
}

/// A count of `what` (vertices or facets), checked against `max` and 4 (the fewest of a
/// closed surface) before anything is reserved for it.
fn count(word: &str, what: &str, max: usize) -> Result<usize, String> {
    if !is_count(word) {
        return Err(format!("{} is not a count of {what}", quoted(word)));
    }
    // Digits only: a number too large for u64 is too large for the limit too.
    let n = word.parse::<u64>().unwrap_or(u64::MAX);
    if n > max as u64 {
        let shown = if word.len() <= 24 {
            word.to_string()
        } else {
            quoted(word)
        };
        return Err(format!(
            "{shown} {what} declared: touchdown reads shape models of at most {max} {what}"
        ));
    }
    if n < 4 {
        return Err(format!(
            "{n} {what} declared: a closed surface has at least 4"
        ));
    }
    // n <= max, which fits usize.
    Ok(n as usize)
}

/// The first line's counts: `NV NF` (the facet count `Some`) or `NV`.
fn counts(w: &[&str; 4], n: usize) -> Result<(usize, Option<usize>), String> {
    if !matches!(n, 1 | 2) {
        return Err(format!(
            "a plate model starts with its counts, 'NV NF' or 'NV' (vertices, facets), not \
             {n} words"
        ));
    }
    let vertices = count(w[0], "vertices", MAX_VERTICES)?;
    let facets = if n == 2 {
        Some(count(w[1], "facets", MAX_FACETS)?)
    } else {
        None
    };
    Ok((vertices, facets))
}

/// Checks a row's number against its place: row `k` (1-based) of `total` `what` (plural).
fn row_number(word: &str, k: usize, total: usize, what: [&str; 2]) -> Result<(), String> {
    if word.parse::<u64>().ok() == Some(k as u64) {
        return Ok(());
    }
    let [one, many] = what;
    Err(format!(
        "expected {one} {k} (the rows number the {total} {many} 1 to {total} in order), \
         found {}",
        quoted(word)
    ))
}

/// A vertex row `i x y z`, the `k`-th (1-based) of `total`, in metres.
fn vertex(text: &str, k: usize, total: usize, scale: f64) -> Result<[f64; 3], String> {
    let (w, n) = words(text);
    if n != 4 {
        return Err(format!(
            "a vertex row has 4 numbers (i x y z), not {n}: vertex {k} of {total} expected"
        ));
    }
    row_number(w[0], k, total, ["vertex", "vertices"])?;
    let mut xyz = [0.0; 3];
    for (x, word) in xyz.iter_mut().zip(&w[1..]) {
        let value: f64 = word
            .parse()
            .map_err(|_| format!("{} is not a number", quoted(word)))?;
        if !value.is_finite() {
            return Err(format!("{} is not a finite number", quoted(word)));
        }
        *x = value * scale;
        if !x.is_finite() {
            return Err(format!("{} overflows in metres", quoted(word)));
        }
    }
    Ok(xyz)
}

/// A facet row `j a b c`, the `k`-th (1-based) of `total`, its vertices 0-based.
fn facet(text: &str, k: usize, total: usize, vertices: usize) -> Result<[u32; 3], String> {
    let (w, n) = words(text);
    if n != 4 {
        return Err(format!(
            "a facet row has 4 numbers (j a b c), not {n}: facet {k} of {total} expected"
        ));
    }
    row_number(w[0], k, total, ["facet", "facets"])?;
    let mut abc = [0u32; 3];
    for (v, word) in abc.iter_mut().zip(&w[1..]) {
        let number: u64 = word
            .parse()
            .map_err(|_| format!("{} is not a vertex number", quoted(word)))?;
        if number == 0 {
            return Err("vertex number 0: plate models number vertices from 1".into());
        }
        if number > vertices as u64 {
            return Err(format!(
                "vertex {number} does not exist (the model has {vertices} vertices)"
            ));
        }
        // number <= vertices <= MAX_VERTICES, far below u32::MAX.
        *v = u32::try_from(number - 1).map_err(|_| format!("vertex {number} is out of range"))?;
    }
    Ok(abc)
}

/// What the reader expects next.
enum Expect {
    /// The counts: `NV NF` or `NV`.
    Counts,
    /// Vertex row `k` (1-based).
    Vertex(usize),
    /// The facet count of the second variant.
    FacetCount,
    /// Facet row `k` (1-based).
    Facet(usize),
    /// Nothing but blank lines.
    End,
}

/// Reads a plate model from `reader`, its file named `name` in messages.
pub(super) fn parse<R: BufRead>(reader: R, name: &str, scale: f64) -> Result<Mesh, ShapeError> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(ShapeError::Value(format!(
            "metres per unit of the shape model {name} must be a positive number, not {scale}"
        )));
    }
    let mut lines = Lines::new(reader, name);
    let mut mesh = Mesh::default();
    let (mut nv, mut nf) = (0usize, 0usize);
    let (mut counts_line, mut facets_line) = (0usize, 0usize);
    let mut expect = Expect::Counts;
    while let Some((line, text)) = lines.next()? {
        let step = match expect {
            Expect::Counts => {
                counts_line = line;
                facets_line = line;
                let (w, n) = words(text);
                counts(&w, n).map(|(v, f)| {
                    (nv, nf) = (v, f.unwrap_or(0));
                    mesh.vertices.reserve(nv.min(RESERVE_AHEAD));
                    mesh.facets.reserve(nf.min(RESERVE_AHEAD));
                    Expect::Vertex(1)
                })
            }
            Expect::Vertex(k) => vertex(text, k, nv, scale).map(|xyz| {
                mesh.vertices.push(xyz);
                match (k < nv, nf > 0) {
                    (true, _) => Expect::Vertex(k + 1),
                    (false, true) => Expect::Facet(1),
                    (false, false) => Expect::FacetCount,
                }
            }),
            Expect::FacetCount => {
                facets_line = line;
                let (w, n) = words(text);
                if n == 1 {
                    count(w[0], "facets", MAX_FACETS).map(|f| {
                        nf = f;
                        mesh.facets.reserve(nf.min(RESERVE_AHEAD));
                        Expect::Facet(1)
                    })
                } else {
                    Err(format!(
                        "expected the facet count (one number) after the {nv} vertices \
                         declared on line {counts_line}, found {n} numbers"
                    ))
                }
            }
            Expect::Facet(k) => facet(text, k, nf, nv).map(|abc| {
                mesh.facets.push(abc);
                if k < nf {
                    Expect::Facet(k + 1)
                } else {
                    Expect::End
                }
            }),
            Expect::End => Err(format!(
                "more than the {nf} facets declared on line {facets_line}: the file goes on \
                 after facet {nf}"
            )),
        };
        expect = step.map_err(|reason| lines.error(line, reason))?;
    }
    let end = lines.line + 1;
    let missing = match expect {
        Expect::End => return Ok(mesh),
        Expect::Counts => "empty: a plate model starts with its counts, 'NV NF' or 'NV'".into(),
        Expect::Vertex(k) => {
            format!("the file ends before vertex {k} of the {nv} declared on line {counts_line}")
        }
        Expect::FacetCount => {
            format!("the file ends before the facet count that follows the {nv} vertices")
        }
        Expect::Facet(k) => {
            format!("the file ends before facet {k} of the {nf} declared on line {facets_line}")
        }
    };
    Err(lines.error(end, missing))
}
