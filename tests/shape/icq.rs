//! Gaskell's ICQ files (SPC's `SHAPE.TXT`: the grid size `Q`, then `6 (Q + 1)^2` rows
//! `x y z`, six cube faces of `Q x Q` quadrilaterals): an ellipsoid written as ICQ reads as
//! the OBJ of the same triangles, closes, and its volume approaches the ellipsoid's; its
//! mirror image reads outward; Fortran's `D` exponents; the format chosen by content; bad
//! files refused naming the line, and random and mutated ones read without a panic.

use super::Stream;
use super::plate::{Num, octahedron, plate_b};
use crate::common::TempDir;
use std::collections::HashMap;
use touchdown::shape::{
    MAX_FACETS, MAX_LINE_BYTES, MAX_VERTICES, Mesh, Polyhedron, parse_icq, parse_obj, parse_shape,
    read_icq, read_obj, read_shape,
};

/// Where each face lies on the cube `[-1, 1]^3`: its corner `V(0, 0, f)`, the step of `i`
/// and the step of `j` (MODEL.md 13.1; the twelve identities of the SPC documentation hold
/// in it, checked in src/shape/icq.rs).
const FACES: [[[i64; 3]; 3]; 6] = [
    [[-1, -1, 1], [0, 1, 0], [1, 0, 0]],
    [[1, -1, 1], [0, 1, 0], [0, 0, -1]],
    [[-1, -1, 1], [1, 0, 0], [0, 0, -1]],
    [[-1, 1, 1], [0, -1, 0], [0, 0, -1]],
    [[1, 1, 1], [-1, 0, 0], [0, 0, -1]],
    [[1, -1, -1], [0, 1, 0], [-1, 0, 0]],
];

/// The rows of an ICQ model of grid size `q`, in file order (face, `j`, `i`): each point of
/// the cube's grid pushed out onto the ellipsoid of semi-axes `axes` along its direction.
/// Each point is computed from its integer cube coordinates, so every row listing the same
/// point has the same coordinates to the bit.
pub(super) fn ellipsoid_rows(q: usize, axes: [f64; 3]) -> Vec<[f64; 3]> {
    let mut rows = Vec::new();
    let n = q as i64;
    for [o, u, w] in FACES {
        for j in 0..=n {
            for i in 0..=n {
                let p: [f64; 3] =
                    std::array::from_fn(|k| (o[k] * n + 2 * i * u[k] + 2 * j * w[k]) as f64);
                let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                rows.push(std::array::from_fn(|k| p[k] / r * axes[k]));
            }
        }
    }
    rows
}

/// The ICQ text of the rows: `q`, then a row `x y z` a line, each number written by
/// `form`, lines ended by `eol`.
pub(super) fn icq_text(q: usize, rows: &[[f64; 3]], form: Num, eol: &str) -> String {
    let mut s = format!("{q:>5}{eol}");
    for v in rows {
        s += &format!(
            "{} {} {}{eol}",
            super::plate::num(v[0], form),
            super::plate::num(v[1], form),
            super::plate::num(v[2], form)
        );
    }
    s
}

/// The mesh the rows make (in their units), as the format's documentation says: each
/// distinct point (here found by its coordinates, not by the identities) numbered at its
/// first row; each cell `(i, j)`-`(i + 1, j + 1)` split along that diagonal into
/// `(i, j) (i + 1, j + 1) (i + 1, j)` and `(i, j) (i, j + 1) (i + 1, j + 1)`, in the order
/// face, `j`, `i`.
pub(super) fn icq_mesh(q: usize, rows: &[[f64; 3]]) -> Mesh {
    let mut vertices = Vec::new();
    let mut number: HashMap<[u64; 3], u32> = HashMap::new();
    let index: Vec<u32> = rows
        .iter()
        .map(|v| {
            *number.entry(v.map(f64::to_bits)).or_insert_with(|| {
                vertices.push(*v);
                vertices.len() as u32 - 1
            })
        })
        .collect();
    let n = q + 1;
    let mut facets = Vec::new();
    for f in 0..6 {
        let at = |i: usize, j: usize| index[(f * n + j) * n + i];
        for j in 0..q {
            for i in 0..q {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                facets.push([a, c, b]);
                facets.push([a, d, c]);
            }
        }
    }
    Mesh { vertices, facets }
}

/// Semi-axes (km) of the test ellipsoid: three different ones, none a power of two.
const AXES: [f64; 3] = [3.1, 2.3, 1.7];

fn read(text: &str) -> Mesh {
    parse_icq(text, "t.txt", 1000.0).unwrap_or_else(|e| panic!("{e}"))
}

/// An ellipsoid of grid size 1, 2, 7 and 16 written as ICQ reads as the OBJ file of the
/// triangles its documentation describes, to the bit (the same numbers times the same 1000),
/// by content as well as as ICQ; the mesh is closed, manifold and outward, with `12 Q^2`
/// facets and `6 Q^2 + 2` vertices.
#[test]
fn an_icq_model_reads_as_the_obj_of_its_triangles() {
    for q in [1, 2, 7, 16] {
        let rows = ellipsoid_rows(q, AXES);
        assert_eq!(rows.len(), 6 * (q + 1) * (q + 1));
        let text = icq_text(q, &rows, Num::Plain, "\n");
        let obj = super::plate::obj_text(&icq_mesh(q, &rows), Num::Plain);
        let mesh = read(&text);
        assert_eq!(mesh, parse_obj(&obj, "t.obj", 1000.0).unwrap(), "Q {q}");
        assert_eq!(parse_shape(&text, "t.txt", 1000.0).unwrap(), mesh, "Q {q}");
        assert_eq!(mesh.facets.len(), 12 * q * q);
        assert_eq!(mesh.vertices.len(), 6 * q * q + 2);
        let checked = mesh.check().unwrap_or_else(|e| panic!("Q {q}: {e}"));
        assert!(checked.volume_m3() > 0.0);
    }
}

/// The checked mesh's volume approaches the ellipsoid's, `4/3 pi a b c`, from below (its
/// vertices lie on the ellipsoid, a convex surface: the polyhedron is inscribed). The
/// ellipsoid is the sphere's image under `diag(a, b, c)`, which maps the triangles of one
/// onto those of the other and multiplies every volume by `a b c`: the relative error is
/// the unit sphere's, a deficit of about `k / Q^2` (a cap's depth goes as the square of the
/// cell's size). Measured, `Q^2` times the error: 0.632 (Q 1, the inscribed cube), 0.934
/// (2), 1.139 (4), 1.192 (7), 1.198 (8), 1.214 (16), 1.218 (32), settling near 1.22. The
/// bounds 0.6 / Q^2 to 1.3 / Q^2 hold these with a margin of 5 % at either end; a wrong
/// split of the cells or a vertex moved off the ellipsoid by more than about a tenth of the
/// caps' depth leaves them, and the error shrinks at every larger grid.
#[test]
fn the_volume_approaches_the_ellipsoids_as_the_grid_grows() {
    let exact = 4.0 / 3.0 * std::f64::consts::PI * AXES.iter().product::<f64>() * 1e9;
    let mut last = f64::INFINITY;
    for q in [1, 2, 4, 7, 8, 16, 32] {
        let text = icq_text(q, &ellipsoid_rows(q, AXES), Num::Plain, "\n");
        let volume = read(&text).check().unwrap().volume_m3();
        let error = 1.0 - volume / exact;
        let k = error * (q * q) as f64;
        eprintln!("Q {q}: relative error {error:.3e}, Q^2 times it {k:.3}");
        assert!(error > 0.0, "Q {q}: {volume} above {exact}");
        assert!((0.6..1.3).contains(&k), "Q {q}: relative error {error}");
        assert!(error < last, "Q {q}");
        last = error;
    }
}

/// The identities allow two mirror-image layouts of the faces, and a file does not say which
/// it has: the ellipsoid mirrored (x to -x in every row) reads with every facet reversed,
/// outward, with the same volume.
#[test]
fn a_mirrored_file_still_reads_outward() {
    for q in [1, 3, 8] {
        let rows = ellipsoid_rows(q, AXES);
        let mirrored: Vec<[f64; 3]> = rows.iter().map(|&[x, y, z]| [-x, y, z]).collect();
        let plain = read(&icq_text(q, &rows, Num::Plain, "\n"));
        let mesh = read(&icq_text(q, &mirrored, Num::Plain, "\n"));
        let flipped: Vec<[u32; 3]> = plain.facets.iter().map(|&[a, b, c]| [a, c, b]).collect();
        assert_eq!(mesh.facets, flipped, "Q {q}");
        let xs: Vec<[f64; 3]> = plain.vertices.iter().map(|&[x, y, z]| [-x, y, z]).collect();
        assert_eq!(mesh.vertices, xs, "Q {q}");
        let (a, b) = (plain.check().unwrap(), mesh.check().unwrap());
        assert!(b.volume_m3() > 0.0);
        let (v, w) = (a.volume_m3(), b.volume_m3());
        assert!((v - w).abs() <= 1e-12 * v, "Q {q}: {v} against {w}");
    }
}

/// Numbers as SPC writes them, Fortran's `D` exponent (`1.234D+00`, also `d`), in fixed
/// columns with CRLF line ends, read as the same numbers in Rust's exponent form; blank
/// lines anywhere and a UTF-8 byte order mark change nothing.
#[test]
fn fortran_exponents_and_blank_lines_read() {
    let q = 4;
    let rows = ellipsoid_rows(q, AXES);
    let e = icq_text(q, &rows, Num::Exp, "\n");
    assert!(e.contains("E-1 "), "{e}");
    let fortran: String = e
        .lines()
        .enumerate()
        .map(|(k, line)| {
            let d = if k % 2 == 0 { "D" } else { "d" };
            let cols: Vec<String> = line
                .split_whitespace()
                .map(|w| format!("{:>24}", w.replace('E', d)))
                .collect();
            cols.concat() + "\r\n"
        })
        .collect();
    assert!(fortran.contains("D-1") && fortran.contains("d-1") && !fortran.contains('E'));
    let mesh = read(&e);
    assert_eq!(read(&fortran), mesh);
    assert_eq!(mesh, read(&icq_text(q, &rows, Num::Plain, "\n")));
    let spaced = format!("\n \r\n{}\n\n", e.replace('\n', "\n\n"));
    assert_eq!(parse_shape(&spaced, "t.txt", 1000.0).unwrap(), mesh);
    let marked = format!("\u{feff}{fortran}");
    assert_eq!(parse_shape(&marked, "t.txt", 1000.0).unwrap(), mesh);
    // Rows in the fixed columns and `D` exponents SPC writes.
    let head = "   512\n  -0.21392D+00   0.10804D+00   0.16071D+00\n";
    let e = parse_shape(head, "SHAPE.TXT", 1000.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "SHAPE.TXT, line 3: the file ends before face 0's vertex (i 1, j 0), row 2 of the \
         1579014 of grid size 512 (line 1)"
    );
}

fn refused(text: &str) -> String {
    match parse_shape(text, "t.txt", 1000.0) {
        Ok(m) => panic!("{text:?} read as {m:?}"),
        Err(e) => e.to_string(),
    }
}

/// The ellipsoid of grid size 2 as ICQ lines: line 1 `Q`, then the 54 rows, face `f`'s
/// vertex `(i, j)` on line `2 + 9 f + 3 j + i`.
fn q2_lines() -> Vec<String> {
    icq_text(2, &ellipsoid_rows(2, AXES), Num::Plain, "\n")
        .lines()
        .map(String::from)
        .collect()
}

/// Each bad line is refused naming the file, the line and what is wrong, with LF or CRLF
/// line ends alike.
#[test]
fn bad_icq_files_are_refused_naming_the_line() {
    let good = q2_lines();
    assert_eq!(good.len(), 55);
    let row = |line: usize| good[line - 1].clone();
    // The row with its first coordinate that is not 0 moved by a unit in the last place.
    let moved = |line: usize| {
        let mut w: Vec<String> = row(line).split(' ').map(String::from).collect();
        let k = (0..3)
            .find(|&k| w[k].parse::<f64>().unwrap() != 0.0)
            .unwrap();
        let x: f64 = w[k].parse().unwrap();
        w[k] = format!("{}", f64::from_bits(x.to_bits() + 1));
        w.join(" ")
    };
    // (what, line to change (1-based), its new text (None: removed), the message)
    let cases: Vec<(&str, usize, Option<String>, String)> = vec![
        (
            "grid size 0",
            1,
            Some("0".into()),
            "t.txt, line 1: grid size 0: an ICQ model's grid size Q is at least 1".into(),
        ),
        (
            "a grid size too large",
            1,
            Some("646".into()),
            format!(
                "t.txt, line 1: grid size 646 declared: touchdown reads ICQ models of grid \
                 size at most 645 (12 Q^2 triangles, at most {MAX_FACETS}; 6 (Q + 1)^2 rows, \
                 at most {MAX_VERTICES})"
            ),
        ),
        (
            "a row of two numbers",
            5,
            Some("1.5 0.5".into()),
            "t.txt, line 5: an ICQ row has 3 numbers (x y z), not 2: face 0's vertex (i 0, j 1) \
             expected"
                .into(),
        ),
        (
            "a row of four numbers",
            12,
            Some(format!("{} 1", row(12))),
            "t.txt, line 12: an ICQ row has 3 numbers (x y z), not 4: face 1's vertex (i 1, j 0) \
             expected"
                .into(),
        ),
        (
            "NaN",
            7,
            Some("0.5 NaN 0.5".into()),
            "t.txt, line 7: 'NaN' is not a finite number".into(),
        ),
        (
            "infinity",
            8,
            Some("0.5 0.5 -inf".into()),
            "t.txt, line 8: '-inf' is not a finite number".into(),
        ),
        (
            "a number too large in metres",
            8,
            Some("0.5 0.5 1e307".into()),
            "t.txt, line 8: '1e307' overflows in metres".into(),
        ),
        (
            "not a number",
            9,
            Some("0.5 1.5km 0.5".into()),
            "t.txt, line 9: '1.5km' is not a number".into(),
        ),
        (
            "the last row missing",
            55,
            None,
            "t.txt, line 55: the file ends before face 5's vertex (i 2, j 2), row 54 of the 54 \
             of grid size 2 (line 1)"
                .into(),
        ),
        (
            "a copy on an edge moved by an ulp",
            34,
            Some(moved(34)),
            "t.txt, line 34: face 3's vertex (i 2, j 1) differs from face 2's vertex (i 0, j 1) \
             on line 23, the same point of the surface ("
                .into(),
        ),
        (
            "a corner's third copy moved by an ulp",
            55,
            Some(moved(55)),
            "t.txt, line 55: face 5's vertex (i 2, j 2) differs from face 3's vertex (i 0, j 2) \
             on line 35, the same point of the surface ("
                .into(),
        ),
    ];
    for (what, line, new, message) in cases {
        let mut lines = good.clone();
        match new {
            Some(text) => lines[line - 1] = text,
            None => {
                lines.remove(line - 1);
            }
        }
        let e = refused(&(lines.join("\n") + "\n"));
        assert!(e.starts_with(&message), "{what}: {e}");
        assert_eq!(refused(&(lines.join("\r\n") + "\r\n")), e, "{what}, CRLF");
    }
    // The moved copy's message gives both rows' numbers as parsed.
    let mut lines = good.clone();
    lines[33] = moved(34);
    let e = refused(&lines.join("\n"));
    let [x, y, z] = [0, 1, 2].map(|k| lines[33].split(' ').nth(k).unwrap().to_string());
    let was = &good[22];
    assert!(
        e.contains(&format!(
            "({x} {y} {z} against {was}): an ICQ model lists a point"
        )),
        "{e}"
    );
    // A plate model of one count whose first row lost a number reads as ICQ (one count,
    // then three numbers), and its message says why.
    let plate = "4\n1 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n4\n1 1 3 2\n2 1 2 4\n3 1 4 3\n4 2 3 4\n";
    let e = refused(plate);
    assert!(
        e.starts_with("t.txt, line 3: an ICQ row has 3 numbers (x y z), not 4")
            && e.ends_with("a plate model's rows have four)"),
        "{e}"
    );
    // Interior rows are not copies: one moved is no refusal of the reader's (row 5 of face
    // 0 is its centre, line 2 + 3 + 1).
    let mut lines = good.clone();
    lines[5] = moved(6);
    assert!(parse_shape(&lines.join("\n"), "t.txt", 1000.0).is_ok());

    let text = good.join("\n") + "\n";
    assert_eq!(
        refused(&format!("{text}0.5 0.5 0.5\n\n")),
        "t.txt, line 56: more than the 54 rows of grid size 2 (line 1): the file goes on after \
         face 5's vertex (i 2, j 2)"
    );
    assert!(refused(&format!("{text}\n  x")).starts_with("t.txt, line 57: more than the 54 rows"));
    let truncated = good[..39].join("\n");
    assert_eq!(
        refused(&truncated),
        "t.txt, line 40: the file ends before face 4's vertex (i 2, j 0), row 39 of the 54 of \
         grid size 2 (line 1)"
    );

    // The grid size, as parse_icq reads it (the format's choice sends these elsewhere).
    let rows = good[1..].join("\n");
    for (first, message) in [
        (
            "",
            "t.txt, line 1: empty: an ICQ model starts with its grid size Q",
        ),
        (
            "2 54",
            "t.txt, line 1: an ICQ model starts with its grid size Q alone on its line, not 2 \
             words",
        ),
        (
            "-3",
            "t.txt, line 1: grid size -3: an ICQ model's grid size Q is at least 1",
        ),
        (
            "2.0",
            "t.txt, line 1: '2.0' is not a grid size (a whole number Q",
        ),
        ("+2", "t.txt, line 1: '+2' is not a grid size"),
        (
            "two",
            "t.txt, line 1: 'two' is not a grid size (a whole number Q",
        ),
    ] {
        let text = if first.is_empty() {
            String::new()
        } else {
            format!("{first}\n{rows}\n")
        };
        let e = parse_icq(&text, "t.txt", 1.0).unwrap_err().to_string();
        assert!(e.starts_with(message), "{first:?}: {e}");
    }
    let long = format!("5\n0.5 0.5 0.5{}\n", " ".repeat(MAX_LINE_BYTES));
    assert_eq!(
        parse_icq(&long, "t.txt", 1.0).unwrap_err().to_string(),
        format!("t.txt, line 2: longer than {MAX_LINE_BYTES} bytes")
    );
    // The same by content (a line too long is no row: a plate model's, refused alike).
    assert_eq!(
        refused(&long),
        format!("t.txt, line 2: longer than {MAX_LINE_BYTES} bytes")
    );
    for scale in [0.0, -1.0, f64::NAN] {
        let e = parse_icq(&text, "t.txt", scale).unwrap_err().to_string();
        assert!(e.contains("metres per unit"), "{e}");
    }
}

/// A grid size above the limits is refused on its line before a row is read or anything
/// reserved for it (a two-line file claiming 10^40 rows is refused naming the size); the
/// largest accepted is read row by row.
#[test]
fn a_hostile_grid_size_is_refused_before_anything_is_reserved() {
    let row = "0.5 0.5 0.5\n";
    let digits = "9".repeat(40);
    let e = refused(&format!("{digits}\n{row}"));
    assert!(
        e.starts_with("t.txt, line 1: grid size '999999999999999999999999...' declared"),
        "{e}"
    );
    let e = refused(&format!("1000000000000\n{row}"));
    assert!(
        e.starts_with("t.txt, line 1: grid size 1000000000000 declared: touchdown reads ICQ"),
        "{e}"
    );
    assert_eq!(
        refused(&format!("645\n{row}{row}")),
        "t.txt, line 4: the file ends before face 0's vertex (i 2, j 0), row 3 of the 2503896 \
         of grid size 645 (line 1)"
    );
}

/// The format is chosen by content, not by name: after a first line of one count, a line
/// of three numbers makes an ICQ model and one of four (or anything else) a plate model,
/// read as before; blank lines between them keep their numbers.
#[test]
fn an_icq_file_is_told_apart_by_content() {
    let dir = TempDir::new("shape-icq-sniff");
    let q = 3;
    let text = icq_text(q, &ellipsoid_rows(q, AXES), Num::Plain, "\n");
    let named_obj = dir.write("shape.obj", &text);
    let named_tab = dir.write("SHAPE.tab", &text);
    let icq = read_icq(&named_obj, 1000.0).unwrap();
    assert_eq!(read_shape(&named_obj, 1000.0).unwrap(), icq);
    assert_eq!(read_shape(&named_tab, 1000.0).unwrap(), icq);
    assert!(read_obj(&named_obj, 1000.0).is_err());
    let e = read_icq(&dir.join("missing.txt"), 1.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("cannot read ") && e.contains("missing.txt"),
        "{e}"
    );

    // A plate model of one count (SBMT .plt) is still one, blank lines or not.
    let km = octahedron(1.5);
    let plt = plate_b(&km, Num::Plain, "\n");
    assert_eq!(
        parse_shape(&plt, "t.plt", 1000.0).unwrap(),
        octahedron(1500.0)
    );
    let spaced = plt.replacen('\n', "\n\n \n", 1);
    assert_eq!(
        parse_shape(&spaced, "t.plt", 1000.0).unwrap(),
        octahedron(1500.0)
    );
    // Blank lines before and between keep their numbers, in either format.
    for (text, message) in [
        (
            "\n\n2\n\n\r\n0.5 0 0\n0 x 0\n",
            "t.txt, line 7: 'x' is not a number",
        ),
        (
            "\n5\n\n0.5 0 0 1\n",
            "t.txt, line 4: expected vertex 1 (the rows number the 5 vertices",
        ),
        (
            "\n4\n\n1 0 0 0\n2 1 x 0\n",
            "t.txt, line 5: 'x' is not a number",
        ),
        // Three words that are no numbers: a plate row, refused as one.
        (
            "4\n\n1 0 x\n",
            "t.txt, line 3: a vertex row has 4 numbers (i x y z), not 3",
        ),
        // A count alone and nothing after it: a plate model's (as before).
        (
            "\n5\n\n",
            "t.txt, line 4: the file ends before vertex 1 of the 5",
        ),
        // Fortran's exponent counts as a number.
        (
            "2\n1D0 0 0\n1 2\n",
            "t.txt, line 3: an ICQ row has 3 numbers (x y z), not 2",
        ),
    ] {
        let e = parse_shape(text, "t.txt", 1.0).unwrap_err().to_string();
        assert!(e.starts_with(message), "{text:?}: {e}");
    }
    // A row `i x y z` of four words is a plate row, so "5\n0.5 0 0 1" is a plate model
    // whose row is numbered wrong; "5\n0.5 0 0" an ICQ model whose file ends.
    assert!(refused("5\n0.5 0 0 1\n").contains("expected vertex 1"));
    assert!(refused("5\n0.5 0 0\n").contains("the file ends before face 0's vertex (i 1, j 0)"));
}

/// Read (by content, and as ICQ), check and, if sound, evaluate: an answer and never a
/// panic.
fn survive(text: &str) -> bool {
    let _ = parse_icq(text, "fuzz.txt", 1000.0);
    let Ok(mesh) = parse_shape(text, "fuzz.txt", 1000.0) else {
        return false;
    };
    let Ok(checked) = mesh.check() else {
        return false;
    };
    let poly = Polyhedron::new(checked, 1000.0).unwrap();
    assert!(poly.field([1e4, 2e4, 3e4]).potential_m2_s2.is_finite());
    true
}

/// Sound ICQ files (plain and Fortran numbers) with bytes replaced, words replaced by
/// hostile ones, lines removed, repeated or swapped, and cut at every byte: read and checked
/// without a panic (seeded). Only the whole file (with or without its last newline) is
/// sound when cut: its last row is a copy of a corner, which a shorter number moves.
#[test]
fn random_and_mutated_icq_files_never_panic() {
    let mut s = Stream(0x9e37_79b9_7f4a_7c15);
    let rows = ellipsoid_rows(2, AXES);
    let files = [
        icq_text(2, &rows, Num::Plain, "\n"),
        icq_text(2, &rows, Num::Exp, "\r\n").replace('E', "D"),
    ];
    let bytes = b"0123456789 \n\r\t-+.eEdD#xv\xff";
    let words = [
        "0",
        "1",
        "2",
        "-1",
        "645",
        "646",
        "99999999999999999999",
        "1e308",
        "-1e308",
        "1D999",
        "nan",
        "inf",
        "1.",
        ".",
        "-",
        "D",
        "v",
        "",
    ];
    for file in &files {
        assert!(survive(file));
    }
    let sound = super::fuzz(
        &mut s,
        &files,
        (bytes, &words),
        [600, 600, 300, 1000],
        survive,
    );
    // Some changed bytes leave the body sound (a digit of an interior row): the mutations
    // reach the end of the reader, not only its first refusals.
    assert!(sound > 0);
}
