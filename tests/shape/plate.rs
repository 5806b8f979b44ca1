//! Vertex-facet plate files (PDS `.tab`: `NV NF` first; SBMT `.plt`: `NV`, the vertices,
//! `NF`, the facets): the same body read from OBJ and both variants, the format chosen by
//! content, and `touchdown site` on the same body in both formats. Refusals and random
//! input: plate_refusals.rs.

use super::icosphere;
use crate::common::{TempDir, arrow_column, touchdown};
use touchdown::shape::{
    MAX_LINE_BYTES, Mesh, parse_obj, parse_plate, parse_shape, read_obj, read_shape,
};

/// How the numbers of a file are written.
#[derive(Clone, Copy)]
pub(super) enum Num {
    /// Rust's shortest form that reads back the same: `-0.15153`.
    Plain,
    /// The same in exponent form: `-1.5153E-1`.
    Exp,
    /// Five decimals right-aligned in 15 columns, as PDS tables have them (exact only for
    /// numbers with five decimals or fewer).
    Fixed,
}

pub(super) fn num(x: f64, form: Num) -> String {
    match form {
        Num::Plain => format!("{x}"),
        Num::Exp => format!("{x:E}"),
        Num::Fixed => format!("{x:15.5}"),
    }
}

/// The mesh (in the file's units) as OBJ text.
pub(super) fn obj_text(mesh: &Mesh, form: Num) -> String {
    let mut s = String::from("# a test body\n");
    for v in &mesh.vertices {
        s += &format!(
            "v {} {} {}\n",
            num(v[0], form),
            num(v[1], form),
            num(v[2], form)
        );
    }
    for f in &mesh.facets {
        s += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s
}

/// The rows `i x y z` and `j a b c` of a plate file, right-aligned as PDS tables are.
fn rows(mesh: &Mesh, form: Num) -> (Vec<String>, Vec<String>) {
    let vertices = mesh.vertices.iter().enumerate().map(|(i, v)| {
        format!(
            "{:>10} {:>15} {:>15} {:>15}  ",
            i + 1,
            num(v[0], form),
            num(v[1], form),
            num(v[2], form)
        )
    });
    let facets = mesh.facets.iter().enumerate().map(|(j, f)| {
        format!(
            "{:>10} {:>10} {:>10} {:>10}",
            j + 1,
            f[0] + 1,
            f[1] + 1,
            f[2] + 1
        )
    });
    (vertices.collect(), facets.collect())
}

/// Variant A (PDS `.tab`): `NV NF`, the vertices, the facets; lines ended by `eol`.
pub(super) fn plate_a(mesh: &Mesh, form: Num, eol: &str) -> String {
    let (v, f) = rows(mesh, form);
    let head = format!("{:>12} {:>12}", v.len(), f.len());
    let lines: Vec<String> = [vec![head], v, f].concat();
    lines.join(eol) + eol
}

/// Variant B (SBMT `.plt`): `NV`, the vertices, `NF`, the facets; lines ended by `eol`.
pub(super) fn plate_b(mesh: &Mesh, form: Num, eol: &str) -> String {
    let (v, f) = rows(mesh, form);
    let lines: Vec<String> = [
        vec![format!("{}", v.len())],
        v,
        vec![format!("  {}", f.len())],
        f,
    ]
    .concat();
    lines.join(eol) + eol
}

/// The regular octahedron of half-diagonal `h`, facets counter-clockwise from outside.
pub(super) fn octahedron(h: f64) -> Mesh {
    Mesh {
        vertices: vec![
            [h, 0.0, 0.0],
            [-h, 0.0, 0.0],
            [0.0, h, 0.0],
            [0.0, -h, 0.0],
            [0.0, 0.0, h],
            [0.0, 0.0, -h],
        ],
        facets: vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ],
    }
}

fn read(text: &str, scale: f64) -> Mesh {
    parse_shape(text, "t.tab", scale).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The octahedron (coordinates exact in binary and in five decimals) and an icosphere
/// (coordinates of 16-17 digits) in km, written as OBJ, as variant A (LF, padded columns,
/// blank lines and trailing spaces) and as variant B (CRLF, exponent numbers): every form
/// reads as the same mesh, facets and vertices alike.
#[test]
fn the_same_body_reads_the_same_from_obj_and_both_plate_variants() {
    let km = octahedron(1.5);
    let metres = octahedron(1500.0);
    let forms = [
        ("OBJ", obj_text(&km, Num::Plain)),
        ("A, fixed", plate_a(&km, Num::Fixed, "\n")),
        (
            "A, blank lines",
            format!("\n  \n{}\n\n", plate_a(&km, Num::Plain, "\n\n")),
        ),
        ("B, CRLF, exponents", plate_b(&km, Num::Exp, "\r\n")),
    ];
    for (what, text) in &forms {
        // 1.5 km is 1500 m exactly: the meshes are equal to the bit.
        assert_eq!(read(text, 1000.0), metres, "{what}:\n{text}");
    }
    assert_eq!(parse_plate(&forms[3].1, "t.plt", 1000.0).unwrap(), metres);
    assert!(forms[3].1.contains(" 1.5E0  \r\n") && forms[1].1.contains(" 1.50000 "));

    // The icosphere's coordinates are not exact in decimal: each file writes the same f64
    // in a form that reads back to it (shortest or exponent), and both readers multiply it
    // by the same 1000, so all three meshes are equal to the bit.
    let sphere = icosphere(30.0, 2);
    let obj = read(&obj_text(&sphere, Num::Plain), 1000.0);
    let a = read(&plate_a(&sphere, Num::Plain, "\n"), 1000.0);
    let b = read(&plate_b(&sphere, Num::Exp, "\r\n"), 1000.0);
    assert_eq!(a, obj);
    assert_eq!(b, obj);
    assert_eq!(obj.facets, sphere.facets);
    assert_eq!(obj.vertices.len(), 162);
    // Against the icosphere made in metres: x * 30 / r * 1000 and x * 30000 / r round
    // differently, by a few units in the last place (1e-15 relative); 1e-12 of the radius
    // allows for that and nothing else (a wrong row or coordinate moves a vertex by 1e-2 or
    // more of it).
    let exact = icosphere(30_000.0, 2);
    for (k, (p, q)) in b.vertices.iter().zip(&exact.vertices).enumerate() {
        for i in 0..3 {
            assert!(
                (p[i] - q[i]).abs() <= 1e-12 * 30_000.0,
                "vertex {}: {p:?} against {q:?}",
                k + 1
            );
        }
    }
    b.check().expect("a sound mesh");
}

/// A PDS table's first lines as published (Itokawa's ver64q.tab) read as variant A.
#[test]
fn a_pds_tables_rows_are_read_as_published() {
    let text = "       25350        49152\r\n         1       -0.15153        0.08183        \
                0.07523\r\n         2       -0.14726        0.08251        0.07657\r\n";
    let e = parse_shape(text, "ver64q.tab", 1000.0)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "ver64q.tab, line 4: the file ends before vertex 3 of the 25350 declared on line 1"
    );
    let whole = "4 4\n1 -0.15153 0.08183 0.07523\n2 -1.4726E-01 0.08251 0.07657\n\
                 3 0 0 0\n4 0 0 1\n1 1 2 3\n2 1 3 4\n3 1 4 2\n4 2 4 3\n";
    let mesh = parse_plate(whole, "t.tab", 1000.0).unwrap();
    let v: f64 = "-0.15153".parse().unwrap();
    assert_eq!(mesh.vertices[0][0], v * 1000.0);
    let w: f64 = "-0.14726".parse().unwrap();
    assert_eq!(mesh.vertices[1][0], w * 1000.0);
    assert_eq!(mesh.facets[3], [1, 3, 2]);
}

/// The format is chosen by the first line that is not blank, not by the file's name; an
/// OBJ file (sound or not) reads as `read_obj` reads it, to the same mesh or message. (A
/// first line of one or two numbers that are no counts, `-1 2`, is a plate model's
/// header refused: `plate_refusals`.)
#[test]
fn the_format_is_chosen_by_content() {
    let dir = TempDir::new("shape-plate-sniff");
    let km = octahedron(1.5);
    let named_obj = dir.write("plate.obj", &plate_b(&km, Num::Plain, "\n"));
    let named_tab = dir.write("obj.tab", &obj_text(&km, Num::Plain));
    assert_eq!(read_shape(&named_obj, 1000.0).unwrap(), octahedron(1500.0));
    assert_eq!(read_shape(&named_tab, 1000.0).unwrap(), octahedron(1500.0));
    assert!(read_obj(&named_obj, 1.0).is_err());

    let long = format!("{}\nv 0 0 0\n", " ".repeat(MAX_LINE_BYTES + 5));
    let objs = [
        obj_text(&km, Num::Plain),
        format!("\r\n\n  \n{}", obj_text(&km, Num::Exp)),
        "v 0 0 0\nv 1 x 0\n".into(),
        "\n\nl 1 2\n".into(),
        "\n\n 12 x\n".into(),
        "1 2 3\n".into(),
        String::new(),
        "\n \n".into(),
        long,
        format!("\n{}x\nv 0 0 0\n", "1".repeat(MAX_LINE_BYTES + 1)),
    ];
    for (k, text) in objs.iter().enumerate() {
        let path = dir.write(&format!("{k}.obj"), text);
        let via_obj = read_obj(&path, 1000.0).map_err(|e| e.to_string());
        assert_eq!(
            read_shape(&path, 1000.0).map_err(|e| e.to_string()),
            via_obj
        );
        assert_eq!(
            parse_shape(text, "t.obj", 1000.0),
            parse_obj(text, "t.obj", 1000.0)
        );
    }
    let binary = dir.join("binary.obj");
    std::fs::write(&binary, b"\n\xff 4\n").unwrap();
    let e = read_shape(&binary, 1.0).unwrap_err().to_string();
    assert_eq!(e, format!("{}, line 2: not text (UTF-8)", binary.display()));
    let e = read_shape(&dir.join("missing.tab"), 1.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("cannot read ") && e.contains("missing.tab"),
        "{e}"
    );
    for scale in [0.0, -1.0, f64::NAN] {
        let e = read_shape(&named_obj, scale).unwrap_err().to_string();
        assert!(e.contains("metres per unit"), "{e}");
        let e = parse_plate("4 4\n", "t.tab", scale)
            .unwrap_err()
            .to_string();
        assert!(e.contains("metres per unit"), "{e}");
    }
    // Blank lines before the counts keep their numbers: the bad row is line 5.
    let e = parse_shape("\n\r\n4\n1 0 0 0\n2 0 x 0\n", "t.plt", 1.0)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "t.plt, line 5: 'x' is not a number");
}

/// `touchdown site` on the same icosphere written as OBJ and as plate files of both
/// variants (km, the same numbers): the same facets table, column by column, to the bit.
#[test]
fn a_site_map_of_a_plate_file_is_the_map_of_its_obj() {
    let dir = TempDir::new("shape-plate-site");
    let sphere = icosphere(30.0, 2);
    for sub in ["obj", "tab", "plt"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
    }
    dir.write("obj/body.obj", &obj_text(&sphere, Num::Plain));
    dir.write("tab/body.tab", &plate_a(&sphere, Num::Plain, "\n"));
    dir.write("plt/body.plt", &plate_b(&sphere, Num::Exp, "\r\n"));
    let map = |shape: &str, out: &str| {
        let run = touchdown(
            dir.path(),
            &[
                "site",
                shape,
                "--units",
                "km",
                "--density",
                "2000",
                "--spin-period",
                "3.3",
                "--samples",
                "200",
                "--out-dir",
                out,
                "--quiet",
            ],
        );
        assert_eq!(run.code, Some(0), "{run}");
        dir.join(&format!("{out}/facets.arrow"))
    };
    let tables = [
        map("obj/body.obj", "obj-map"),
        map("tab/body.tab", "tab-map"),
        map("plt/body.plt", "plt-map"),
    ];
    let file = std::fs::File::open(&tables[0]).expect("open the table");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    let names: Vec<String> = reader
        .schema()
        .fields()
        .iter()
        .filter(|f| f.data_type() == &arrow_schema::DataType::Float64)
        .map(|f| f.name().clone())
        .collect();
    for name in [
        "slope_deg",
        "gravity_m_s2",
        "p_stable",
        "roughness_deg",
        "area_m2",
    ] {
        assert!(names.iter().any(|n| n == name), "no {name} in {names:?}");
    }
    for name in &names {
        let obj = arrow_column(&tables[0], name).unwrap();
        assert_eq!(obj.len(), 320, "{name}");
        for table in &tables[1..] {
            let plate = arrow_column(table, name).unwrap();
            let same = obj.len() == plate.len()
                && obj
                    .iter()
                    .zip(&plate)
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{name} differs in {}", table.display());
        }
    }

    // A bad plate file is refused with the file and line, exit code 2, no map.
    let mut bad = plate_a(&sphere, Num::Plain, "\n");
    bad = bad.replacen("\n         3 ", "\n         4 ", 1);
    dir.write("bad.tab", &bad);
    let run = touchdown(
        dir.path(),
        &[
            "site",
            "bad.tab",
            "--units",
            "km",
            "--density",
            "2000",
            "--spin-period",
            "5",
            "--out-dir",
            "bad",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("bad.tab, line 4: expected vertex 3 (the rows number the 162 vertices"),
        "{run}"
    );
    assert!(!dir.join("bad/sweep.arrow").exists());
}
