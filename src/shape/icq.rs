//! Gaskell's ICQ ("implicitly connected quadrilaterals") shape models, read line by line into
//! a [`Mesh`] in metres: the form of the stereophotoclinometry (SPC) models, the PDS's
//! `SHAPE.TXT` files.
//!
//! The first line that is not blank holds the grid size `Q` alone; then `6 (Q + 1)^2` rows
//! `x y z` (whitespace-separated numbers, exponent form accepted, also Fortran's `D` as SPC
//! writes it, `1.234D+00`), the vertex `V(i, j, f)` of face `f` = 0 to 5 (0 the top, 1 to 4
//! around the equator, 5 the bottom), for `j` = 0 to `Q`, for `i` = 0 to `Q`: the six faces
//! of a cube, each a grid of `Q x Q` quadrilaterals, mapped onto the body. A point on a
//! border of the faces is listed once per face it belongs to, and the identities of the SPC
//! documentation say which rows are the same point (faces 0-based, each for `I` = 0 to `Q`):
//! `V(I,0,1) = V(I,Q,0)`, `V(I,0,2) = V(0,I,0)`, `V(I,0,3) = V(Q-I,0,0)`,
//! `V(I,0,4) = V(Q,Q-I,0)`, `V(Q,I,2) = V(0,I,1)`, `V(Q,I,3) = V(0,I,2)`,
//! `V(Q,I,4) = V(0,I,3)`, `V(0,I,4) = V(Q,I,1)`, `V(I,0,5) = V(I,Q,1)`,
//! `V(Q,I,5) = V(I,Q,4)`, `V(I,Q,5) = V(Q-I,Q,3)`, `V(0,I,5) = V(Q-I,Q,2)` (the cube's
//! eight corners follow). Every copy must have the coordinates of the point's first row
//! exactly, as parsed (equal as numbers before scaling, so `-0` equals `0`; SPC writes every
//! copy from the same value): a copy that differs is refused naming both rows, since the
//! surface would not be closed.
//!
//! The mesh: each distinct point is a vertex, numbered in the order of its first row (later
//! copies map to that number), `6 Q^2 + 2` vertices. Each cell from `(i, j)` to
//! `(i + 1, j + 1)` of a face is split along that diagonal into the triangles
//! `(i, j) (i + 1, j + 1) (i + 1, j)` and `(i, j) (i, j + 1) (i + 1, j + 1)`, in the order
//! face, `j`, `i`, then the two: `12 Q^2` facets. The identities fix the faces' layout only
//! up to a mirror image, and a file does not say which it is; so the triangles, built so,
//! face outwards when the faces lie as [`FACES`] has them (`V(i, j, 0)` at
//! `(2 j / Q - 1, 2 i / Q - 1, 1)` on the cube `[-1, 1]^3`), and when the mesh's signed
//! volume (`sum a . (b x c) / 6`) comes out negative (the mirror image) every facet
//! `a b c` is reversed to `a c b`. [`Mesh::check`] then checks the mesh as any other; its
//! messages number vertices and facets from 1 in the orders above.
//!
//! Refused, naming the file and the line: a first line that is not a whole number alone; a
//! grid size below 1 or so large that the model would have more than [`MAX_FACETS`]
//! triangles or more than [`MAX_VERTICES`] rows (refused on its line before anything is
//! reserved; at most 65,536 rows are reserved ahead of those read, the border points' table
//! holds `12 Q - 4` of them); a row without exactly three finite numbers (finite in metres
//! too); a file that ends before its last row (naming the face, `i` and `j` missing);
//! anything but blank lines after it; a copy that differs. Lines are at most
//! [`MAX_LINE_BYTES`](super::MAX_LINE_BYTES) bytes, blank lines are ignored.

use super::error::ShapeError;
use super::mesh::{MAX_FACETS, MAX_VERTICES, Mesh};
use super::plate::{Lines, is_count, quoted};
use super::vec3::{cross, dot, sub};
use std::collections::HashMap;
use std::io::BufRead;
use std::path::Path;

/// The most rows reserved ahead of reading them.
const RESERVE_AHEAD: usize = 1 << 16;

/// The largest grid size read (645): its `12 Q^2` triangles at most [`MAX_FACETS`], its
/// `6 (Q + 1)^2` rows at most [`MAX_VERTICES`].
const MAX_GRID: usize = {
    let mut q = 1;
    while 12 * (q + 1) * (q + 1) <= MAX_FACETS && 6 * (q + 2) * (q + 2) <= MAX_VERTICES {
        q += 1;
    }
    q
};

/// Where each face lies on the cube `[-1, 1]^3`: its corner `V(0, 0, f)`, and the unit
/// steps of growing `i` and of growing `j`. The identities hold in it (a unit test checks
/// all twelve), and `i x j` points into the cube on every face. The identities allow its
/// mirror image too: which one a file follows is read from its volume.
const FACES: [[[i32; 3]; 3]; 6] = [
    [[-1, -1, 1], [0, 1, 0], [1, 0, 0]],
    [[1, -1, 1], [0, 1, 0], [0, 0, -1]],
    [[-1, -1, 1], [1, 0, 0], [0, 0, -1]],
    [[-1, 1, 1], [0, -1, 0], [0, 0, -1]],
    [[1, 1, 1], [-1, 0, 0], [0, 0, -1]],
    [[1, -1, -1], [0, 1, 0], [-1, 0, 0]],
];

/// The point `V(i, j, f)` of a grid of size `q` on the cube `[-q, q]^3`, in integers: the
/// same for every row that lists it.
fn cube_point(q: usize, f: usize, i: usize, j: usize) -> [i32; 3] {
    // q <= MAX_GRID: every product fits i32.
    let [q, i, j] = [q, i, j].map(|n| n as i32);
    let [o, u, w] = FACES[f % 6];
    [0, 1, 2].map(|k| o[k] * q + 2 * i * u[k] + 2 * j * w[k])
}

/// Reads the ICQ shape model at `path`, its coordinates multiplied by `metres_per_unit`
/// (1000 for a model in kilometres, as SPC models are). The mesh is not yet checked: see
/// [`Mesh::check`].
pub fn read_icq(path: &Path, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    let (file, name) = super::error::open(path)?;
    parse(file, &name, metres_per_unit)
}

/// Parses the text of an ICQ shape model named `name` (in messages), its coordinates
/// multiplied by `metres_per_unit`. The mesh is not yet checked: see [`Mesh::check`].
pub fn parse_icq(text: &str, name: &str, metres_per_unit: f64) -> Result<Mesh, ShapeError> {
    parse(text.as_bytes(), name, metres_per_unit)
}

/// A number as SPC writes it: Rust's forms (`-1.5`, `1.5e-3`, `1.5E-3`, and `nan`, `inf`,
/// refused later as not finite) or Fortran's double-precision exponent (`1.5D-3`, `1.5d-3`).
pub(super) fn number(word: &str) -> Option<f64> {
    if let Ok(x) = word.parse() {
        return Some(x);
    }
    let at = word.find(['D', 'd'])?;
    // 'D' is one byte: both slices are on character boundaries.
    let fortran = format!("{}e{}", &word[..at], &word[at + 1..]);
    fortran.parse().ok()
}

/// A number of the file for a message: itself, or quoted and cut if long.
fn shown(word: &str) -> String {
    if word.len() <= 24 {
        word.to_string()
    } else {
        quoted(word)
    }
}

/// The grid size `Q`, alone on its line, checked against 1 and [`MAX_GRID`] before
/// anything is reserved for it.
fn grid_size(text: &str) -> Result<usize, String> {
    let mut words = text.split_whitespace();
    let (Some(word), None) = (words.next(), words.next()) else {
        let n = text.split_whitespace().count();
        return Err(format!(
            "an ICQ model starts with its grid size Q alone on its line, not {n} words"
        ));
    };
    let negative = word.strip_prefix('-').is_some_and(is_count);
    if !(is_count(word) || negative) {
        return Err(format!(
            "{} is not a grid size (a whole number Q: each face of the model a grid of Q x Q \
             quadrilaterals)",
            quoted(word)
        ));
    }
    if negative || word.bytes().all(|b| b == b'0') {
        return Err(format!(
            "grid size {}: an ICQ model's grid size Q is at least 1",
            shown(word)
        ));
    }
    // Digits only: a number too large for u64 is too large for the limit too.
    let q = word.parse::<u64>().unwrap_or(u64::MAX);
    if q > MAX_GRID as u64 {
        return Err(format!(
            "grid size {} declared: touchdown reads ICQ models of grid size at most {MAX_GRID} \
             (12 Q^2 triangles, at most {MAX_FACETS}; 6 (Q + 1)^2 rows, at most {MAX_VERTICES})",
            shown(word)
        ));
    }
    // q <= MAX_GRID, which fits usize.
    Ok(q as usize)
}

/// The vertex a row lists, for messages.
#[derive(Clone, Copy)]
struct Place {
    face: usize,
    i: usize,
    j: usize,
}

impl std::fmt::Display for Place {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Place { face, i, j } = self;
        write!(f, "face {face}'s vertex (i {i}, j {j})")
    }
}

/// A row `x y z`, `place`'s, as parsed (in the file's units), each number finite and finite
/// times `scale` too.
fn row(text: &str, place: Place, scale: f64) -> Result<[f64; 3], String> {
    let mut first = [""; 3];
    let mut n = 0;
    for word in text.split_whitespace() {
        if let Some(slot) = first.get_mut(n) {
            *slot = word;
        }
        n += 1;
    }
    if n != 3 {
        // A plate model of one count whose first row lost a number reads as ICQ: say so.
        let plate = if n == 4 {
            " (read as an ICQ model, its first row having three numbers: a plate model's \
             rows have four)"
        } else {
            ""
        };
        return Err(format!(
            "an ICQ row has 3 numbers (x y z), not {n}: {place} expected{plate}"
        ));
    }
    let mut xyz = [0.0; 3];
    for (x, word) in xyz.iter_mut().zip(first) {
        let value = number(word).ok_or_else(|| format!("{} is not a number", quoted(word)))?;
        if !value.is_finite() {
            return Err(format!("{} is not a finite number", quoted(word)));
        }
        if !(value * scale).is_finite() {
            return Err(format!("{} overflows in metres", quoted(word)));
        }
        *x = value;
    }
    Ok(xyz)
}

/// A point on a border of the faces: its vertex, and its first row.
struct First {
    vertex: u32,
    place: Place,
    line: usize,
}

/// Reads an ICQ model from `reader`, its file named `name` in messages.
pub(super) fn parse<R: BufRead>(reader: R, name: &str, scale: f64) -> Result<Mesh, ShapeError> {
    if !(scale.is_finite() && scale > 0.0) {
        return Err(ShapeError::Value(format!(
            "metres per unit of the shape model {name} must be a positive number, not {scale}"
        )));
    }
    let mut lines = Lines::new(reader, name);
    let Some((q_line, text)) = lines.next()? else {
        let end = lines.line + 1;
        return Err(lines.error(
            end,
            "empty: an ICQ model starts with its grid size Q".into(),
        ));
    };
    let q = grid_size(text).map_err(|reason| lines.error(q_line, reason))?;
    let n = q + 1;
    let rows = 6 * n * n;
    let mut mesh = Mesh::default();
    // The coordinates as parsed, scaled at the end: a copy is compared before scaling.
    mesh.vertices.reserve((6 * q * q + 2).min(RESERVE_AHEAD));
    mesh.facets.reserve((12 * q * q).min(RESERVE_AHEAD));
    // The vertex of each row of the face being read.
    let mut face: Vec<u32> = Vec::with_capacity((n * n).min(RESERVE_AHEAD));
    let mut border: HashMap<[i32; 3], First> = HashMap::new();
    for f in 0..6 {
        face.clear();
        for j in 0..n {
            for i in 0..n {
                let place = Place { face: f, i, j };
                let Some((line, text)) = lines.next()? else {
                    let k = (f * n + j) * n + i + 1;
                    let end = lines.line + 1;
                    return Err(lines.error(
                        end,
                        format!(
                            "the file ends before {place}, row {k} of the {rows} of grid size \
                             {q} (line {q_line})"
                        ),
                    ));
                };
                let xyz = row(text, place, scale).map_err(|reason| lines.error(line, reason))?;
                // At most 6 (Q + 1)^2 <= MAX_VERTICES vertices: the number fits u32.
                let next = mesh.vertices.len() as u32;
                let vertex = if 0 < i && i < q && 0 < j && j < q {
                    mesh.vertices.push(xyz);
                    next
                } else {
                    let point = cube_point(q, f, i, j);
                    if let Some(first) = border.get(&point) {
                        let was = mesh.vertices[first.vertex as usize];
                        if was != xyz {
                            let [x, y, z] = xyz;
                            let [a, b, c] = was;
                            return Err(lines.error(
                                line,
                                format!(
                                    "{place} differs from {} on line {}, the same point of \
                                     the surface ({x} {y} {z} against {a} {b} {c}): an ICQ \
                                     model lists a point on its faces' borders once per \
                                     face, each time the same",
                                    first.place, first.line
                                ),
                            ));
                        }
                        first.vertex
                    } else {
                        mesh.vertices.push(xyz);
                        border.insert(
                            point,
                            First {
                                vertex: next,
                                place,
                                line,
                            },
                        );
                        next
                    }
                };
                face.push(vertex);
            }
        }
        for j in 0..q {
            for i in 0..q {
                let at = |i: usize, j: usize| face[j * n + i];
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                mesh.facets.push([a, c, b]);
                mesh.facets.push([a, d, c]);
            }
        }
    }
    if let Some((line, _)) = lines.next()? {
        return Err(lines.error(
            line,
            format!(
                "more than the {rows} rows of grid size {q} (line {q_line}): the file goes on \
                 after face 5's vertex (i {q}, j {q})"
            ),
        ));
    }
    for v in &mut mesh.vertices {
        *v = v.map(|x| x * scale);
    }
    if signed_volume(&mesh) < 0.0 {
        for facet in &mut mesh.facets {
            facet.swap(1, 2);
        }
    }
    Ok(mesh)
}

/// Six times the volume the facets enclose, signed: positive when they face outwards
/// (taken about the first vertex, which a closed surface's volume does not depend on).
fn signed_volume(mesh: &Mesh) -> f64 {
    let o = mesh.vertices.first().copied().unwrap_or_default();
    let at = |k: u32| sub(mesh.vertices.get(k as usize).copied().unwrap_or(o), o);
    mesh.facets
        .iter()
        .map(|&[a, b, c]| dot(at(a), cross(at(b), at(c))))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::{FACES, MAX_GRID, cube_point, number};
    use crate::shape::mesh::{MAX_FACETS, MAX_VERTICES};
    use std::collections::HashSet;

    #[test]
    fn the_largest_grid_size_is_the_last_within_the_limits() {
        const {
            assert!(12 * MAX_GRID * MAX_GRID <= MAX_FACETS);
            assert!(6 * (MAX_GRID + 1) * (MAX_GRID + 1) <= MAX_VERTICES);
            assert!(12 * (MAX_GRID + 1) * (MAX_GRID + 1) > MAX_FACETS);
        }
        assert_eq!(MAX_GRID, 645);
    }

    /// The faces' layout satisfies the twelve identities of the SPC documentation, and the
    /// rows list `6 Q^2 + 2` distinct points, each on the cube's surface; `i x j` points into
    /// the cube on every face.
    #[test]
    fn the_faces_layout_satisfies_the_identities() {
        for q in 1..=6 {
            let v = |i: usize, j: usize, f: usize| cube_point(q, f, i, j);
            for k in 0..=q {
                let r = q - k;
                assert_eq!(v(k, 0, 1), v(k, q, 0), "q {q}, I {k}");
                assert_eq!(v(k, 0, 2), v(0, k, 0), "q {q}, I {k}");
                assert_eq!(v(k, 0, 3), v(r, 0, 0), "q {q}, I {k}");
                assert_eq!(v(k, 0, 4), v(q, r, 0), "q {q}, I {k}");
                assert_eq!(v(q, k, 2), v(0, k, 1), "q {q}, I {k}");
                assert_eq!(v(q, k, 3), v(0, k, 2), "q {q}, I {k}");
                assert_eq!(v(q, k, 4), v(0, k, 3), "q {q}, I {k}");
                assert_eq!(v(0, k, 4), v(q, k, 1), "q {q}, I {k}");
                assert_eq!(v(k, 0, 5), v(k, q, 1), "q {q}, I {k}");
                assert_eq!(v(q, k, 5), v(k, q, 4), "q {q}, I {k}");
                assert_eq!(v(k, q, 5), v(r, q, 3), "q {q}, I {k}");
                assert_eq!(v(0, k, 5), v(r, q, 2), "q {q}, I {k}");
            }
            let mut distinct = HashSet::new();
            for f in 0..6 {
                for j in 0..=q {
                    for i in 0..=q {
                        let p = v(i, j, f);
                        let q = q as i32;
                        assert!(p.iter().all(|x| x.abs() <= q));
                        assert!(p.iter().any(|x| x.abs() == q));
                        distinct.insert(p);
                    }
                }
            }
            assert_eq!(distinct.len(), 6 * q * q + 2);
        }
        for [o, u, w] in FACES {
            let n = [
                u[1] * w[2] - u[2] * w[1],
                u[2] * w[0] - u[0] * w[2],
                u[0] * w[1] - u[1] * w[0],
            ];
            // The face's centre is o + u + w; inwards is towards the origin.
            let centre: Vec<i32> = (0..3).map(|k| o[k] + u[k] + w[k]).collect();
            let inwards: i32 = (0..3).map(|k| n[k] * centre[k]).sum();
            assert!(inwards < 0, "{o:?} {u:?} {w:?}");
        }
    }

    #[test]
    fn numbers_are_read_in_rusts_and_fortrans_forms() {
        assert_eq!(number("1.234D+00"), Some(1.234));
        assert_eq!(number("-1.5d-3"), Some(-1.5e-3));
        assert_eq!(number("2.5E1"), Some(25.0));
        assert_eq!(number(".5D0"), Some(0.5));
        for bad in ["1.5D", "D5", "1D2D3", "1.5x", "", "1.5Q-3"] {
            assert_eq!(number(bad), None, "{bad}");
        }
        assert!(number("NaN").is_some_and(f64::is_nan));
    }
}
