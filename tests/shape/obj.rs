//! OBJ files: the forms read, the lines refused (named by number), the limits, and files
//! read from disk.

use crate::common::TempDir;
use touchdown::shape::{
    MAX_FACETS, MAX_LINE_BYTES, MAX_VERTICES, Mesh, ShapeError, parse_obj, read_obj,
};

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

fn parsed(text: &str) -> Mesh {
    parse_obj(text, "t.obj", 1.0).unwrap_or_else(|e| panic!("{text:?}: {e}"))
}

fn refused(text: &str) -> String {
    match parse_obj(text, "t.obj", 1.0) {
        Ok(m) => panic!("{text:?} read as {m:?}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn facets_with_texture_and_normal_numbers_relative_numbers_and_polygons() {
    let forms = [
        ("f 1/1/1 2/2/2 3/3/3", vec![[0, 1, 2]]),
        ("f 1//4 2//4 3//4", vec![[0, 1, 2]]),
        ("f 1/7 2/8 3/9", vec![[0, 1, 2]]),
        ("f -4 -3 -2", vec![[0, 1, 2]]),
        ("f -1 -4 -3/1/1", vec![[3, 0, 1]]),
        ("f 1 2 3 4", vec![[0, 1, 2], [0, 2, 3]]),
        ("f 4 1 2 3\t", vec![[3, 0, 1], [3, 1, 2]]),
    ];
    for (line, facets) in forms {
        let mesh = parsed(&format!("{SQUARE}{line}\n"));
        assert_eq!(mesh.facets, facets, "{line}");
        assert_eq!(mesh.vertices.len(), 4);
    }
    // A pentagon is a fan of three triangles from its first vertex.
    let mesh = parsed("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n");
    assert_eq!(mesh.facets, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
}

#[test]
fn vertices_comments_ignored_statements_and_units() {
    let text = "# a comment\r\n\r\nmtllib body.mtl\no body\ng part\ns 1\nusemtl rock\n\
                v 1.5 -2 0.25 # trailing\r\n\tv 1e-3 0 0 1.0\nv 0 2 0 0.5 0.5 0.5\n\
                vn 0 0 1\nvt 0.5 0.5\nvp 0.1\nf 1 2 3\n";
    let km = parse_obj(text, "t.obj", 1000.0).unwrap();
    assert_eq!(
        km.vertices,
        vec![
            [1500.0, -2000.0, 250.0],
            [1.0, 0.0, 0.0],
            [0.0, 2000.0, 0.0]
        ]
    );
    assert_eq!(km.facets, vec![[0, 1, 2]]);
    let m = parse_obj(text, "t.obj", 1.0).unwrap();
    assert_eq!(m.vertices[0], [1.5, -2.0, 0.25]);
    for scale in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = parse_obj(text, "t.obj", scale).unwrap_err().to_string();
        assert!(e.contains("metres per unit") && e.contains("t.obj"), "{e}");
    }
}

#[test]
fn bad_lines_are_refused_by_number() {
    let cases = [
        ("v 0 0 0\nv 1 x 0\n", "t.obj, line 2: 'x' is not a number"),
        ("v nan 0 0\n", "t.obj, line 1: 'nan' is not a finite number"),
        (
            "v 0 -inf 0\n",
            "t.obj, line 1: '-inf' is not a finite number",
        ),
        (
            "v 0 0\n",
            "line 1: a vertex has 3 coordinates (x y z, optionally a weight w, or colours r g b), not 2",
        ),
        ("v 0 0 0 1 1\n", "not 5"),
        ("v 0 0 0 1 1 1 1 1 1\n", "not more than 7"),
        (
            &format!("{SQUARE}f 1 2 9\n"),
            "t.obj, line 5: vertex 9 is not defined (4 vertices before this line)",
        ),
        (
            &format!("{SQUARE}\nf 0 1 2\n"),
            "t.obj, line 6: vertex number 0: OBJ numbers vertices from 1",
        ),
        (
            &format!("{SQUARE}f 1 2\n"),
            "line 5: a facet needs at least 3 vertices, not 2",
        ),
        (&format!("{SQUARE}f\n"), "not 0"),
        (
            &format!("{SQUARE}f -5 1 2\n"),
            "relative vertex -5 reaches before the first vertex (4 vertices before this line)",
        ),
        (
            &format!("{SQUARE}f 1 2 99999999999999999999\n"),
            "'99999999999999999999' is not a vertex number",
        ),
        (
            &format!("{SQUARE}f 1 2 4294967297\n"),
            "vertex 4294967297 is not defined",
        ),
        (
            &format!("{SQUARE}f 1 2 -9223372036854775808\n"),
            "reaches before the first vertex",
        ),
        (
            &format!("{SQUARE}f 1 2 /3\n"),
            "'/3' is not a vertex number",
        ),
        (
            "f 1 2 3\nv 0 0 0\n",
            "line 1: vertex 1 is not defined (0 vertices before this line)",
        ),
        (
            "l 1 2\n",
            "t.obj, line 1: unknown statement 'l' (a shape model is read from its v and f lines",
        ),
        (
            "v 0 0 0\ncurv 0 1 1 2\n",
            "line 2: unknown statement 'curv'",
        ),
        ("V 0 0 0\n", "unknown statement 'V'"),
    ];
    for (text, message) in cases {
        let e = refused(text);
        assert!(e.contains(message), "{text:?}: {e}");
    }
    let e = parse_obj("v 1e308 0 0\n", "km.obj", 1000.0)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "km.obj, line 1: '1e308' overflows in metres");
    let long = format!("v 0 0 0\n#{}\n", " ".repeat(MAX_LINE_BYTES));
    assert_eq!(
        refused(&long),
        format!("t.obj, line 2: longer than {MAX_LINE_BYTES} bytes")
    );
    let e = refused(&format!("x{}\n", "\u{7}".repeat(100)));
    assert!(
        e.contains("unknown statement 'x\\u{7}") && e.contains("...'") && e.len() < 300,
        "{e}"
    );
}

/// More than `MAX_VERTICES` vertices, or `MAX_FACETS` triangles (here from long polygon
/// lines), are refused on the line that passes the limit; the limits themselves are read.
#[test]
fn a_huge_model_is_refused_not_allocated() {
    let text = "v 0 0 0\n".repeat(MAX_VERTICES + 1);
    let e = refused(&text);
    assert!(
        e.starts_with(&format!(
            "t.obj, line {}: more than {MAX_VERTICES} vertices",
            MAX_VERTICES + 1
        )),
        "{e}"
    );
    let per_line = 250_000;
    assert_eq!(MAX_FACETS % per_line, 0);
    let polygon = format!("f{}\n", " 1 2".repeat(per_line / 2 + 1));
    let lines = MAX_FACETS / per_line;
    let at_limit = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{}", polygon.repeat(lines));
    assert_eq!(parsed(&at_limit).facets.len(), MAX_FACETS);
    let e = refused(&format!("{at_limit}{polygon}"));
    assert!(
        e.starts_with(&format!(
            "t.obj, line {}: more than {MAX_FACETS} facets",
            3 + lines + 1
        )),
        "{e}"
    );
}

#[test]
fn files_read_from_disk() {
    let dir = TempDir::new("shape-obj");
    let path = dir.write("body.obj", &format!("{SQUARE}f 1 2 3\n"));
    let mesh = read_obj(&path, 1000.0).unwrap();
    assert_eq!(mesh.vertices[2], [1000.0, 1000.0, 0.0]);
    let missing = dir.join("missing.obj");
    let e = read_obj(&missing, 1.0).unwrap_err();
    assert!(matches!(e, ShapeError::Read { .. }), "{e:?}");
    assert!(
        e.to_string()
            .starts_with(&format!("cannot read {}: ", missing.display())),
        "{e}"
    );
    let binary = dir.join("binary.obj");
    std::fs::write(&binary, b"v 0 0 0\nv \xff\xfe 0 0\n").unwrap();
    let e = read_obj(&binary, 1.0).unwrap_err().to_string();
    assert_eq!(e, format!("{}, line 2: not text (UTF-8)", binary.display()));
}
