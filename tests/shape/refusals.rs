//! Meshes refused by the check, each with its message; a sound mesh's geometry; and random
//! or truncated input that must never panic.

use super::{Stream, checked, cube, icosphere, norm};
use std::f64::consts::PI;
use touchdown::shape::{Mesh, Polyhedron, parse_obj};

fn refused(mesh: Mesh) -> String {
    match mesh.check() {
        Ok(_) => panic!("a bad mesh passed"),
        Err(e) => e.to_string(),
    }
}

/// The cube's facets (1-based, vertices 1-based): 1 (1 4 3), 2 (1 3 2), 3 (5 6 7),
/// 4 (5 7 8), 5 (1 2 6), 6 (1 6 5), 7 (2 3 7), 8 (2 7 6), 9 (3 4 8), 10 (3 8 7),
/// 11 (4 1 5), 12 (4 5 8).
#[test]
fn bad_meshes_are_refused_naming_the_first_bad_edge_or_facet() {
    let mut open = cube(1.0);
    open.facets.pop();
    // Facet 12's edges 4-5, 5-8, 8-4 are left with one facet each; the first of them in
    // file order is facet 4's 8-5.
    assert_eq!(
        refused(open),
        "shape model refused: not closed: edge 8-5 (vertices numbered as in the file) \
         belongs to facet 4 only"
    );

    let mut inverted = cube(1.0);
    inverted.facets.iter_mut().for_each(|f| f.reverse());
    assert!(
        refused(inverted).starts_with("shape model refused: inverted: its facets face inwards")
    );

    let mut flipped = cube(1.0);
    flipped.facets[4].reverse();
    assert_eq!(
        refused(flipped),
        "shape model refused: not consistently oriented: facets 2 and 5 both run along edge \
         2-1 from vertex 2 to vertex 1 (one of them winds the other way)"
    );

    let mut repeated = cube(1.0);
    repeated.facets[2] = [4, 4, 6];
    assert_eq!(
        refused(repeated),
        "shape model refused: degenerate facet 3 (vertices 5 5 7): vertex 5 repeats"
    );

    let mut collinear = cube(1.0);
    collinear.vertices.push([0.0, -1.0, -1.0]);
    collinear.facets[0] = [0, 8, 1];
    let e = refused(collinear);
    assert!(
        e.starts_with("shape model refused: degenerate facet 1 (vertices 1 9 2): its area"),
        "{e}"
    );

    let mut fin = cube(1.0);
    fin.vertices.push([0.0, -3.0, -1.0]);
    fin.facets.push([0, 1, 8]);
    assert_eq!(
        refused(fin),
        "shape model refused: not manifold: edge 2-1 is shared by 3 facets (2, 5, 13)"
    );

    // A coordinate whose cube overflows is named as the overflow, at its vertex and the
    // first facet that names it (not as a degenerate facet of a mesh "inf m across").
    let mut far = cube(1.0);
    far.vertices[6][2] = 1e300;
    let e = refused(far);
    assert!(
        e.starts_with(
            "shape model refused: vertex 7 (of facet 3) at [1.0, 1.0, 1e300] m overflows"
        ),
        "{e}"
    );
    assert!(e.contains("at most 1e100 m"), "{e}");

    let mut few = cube(1.0);
    few.facets.truncate(3);
    assert_eq!(
        refused(few),
        "shape model refused: 3 facets: a closed surface needs at least 4"
    );

    let flat = Mesh {
        vertices: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        facets: vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
    };
    assert!(refused(flat).contains("the surface encloses no volume"));

    let mut outside = cube(1.0);
    outside.facets[0][2] = 99;
    assert_eq!(
        refused(outside),
        "shape model refused: facet 1 names vertex 100, but the mesh has 8 vertices"
    );

    let mut nan = cube(1.0);
    nan.vertices[3][1] = f64::NAN;
    assert!(refused(nan).starts_with("shape model refused: vertex 4 is not finite"));

    let e = Polyhedron::new(checked(cube(1.0)), 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("density"), "{e}");
}

/// A sound mesh's geometry: the cube's exactly, the icosphere's between its inscribed and
/// circumscribed spheres.
#[test]
fn a_sound_mesh_has_its_volume_area_and_centre_of_mass() {
    let c = checked(cube(2.0));
    assert_eq!(c.volume_m3(), 64.0);
    assert_eq!(c.surface_area_m2(), 96.0);
    assert!(norm(c.centre_of_mass_m()) <= 1e-15);
    assert_eq!(c.edges().len(), 18);
    for e in c.edges() {
        let [a, b] = e.vertices;
        let runs = |f: u32, x: u32, y: u32| {
            let t = c.mesh().facets[f as usize];
            (0..3).any(|k| t[k] == x && t[(k + 1) % 3] == y)
        };
        assert!(runs(e.facets[0], a, b) && runs(e.facets[1], b, a));
    }
    let s = checked(icosphere(10.0, 3));
    assert_eq!(s.edges().len(), 3 * 1280 / 2);
    assert!(
        s.volume_m3() < 4.0 / 3.0 * PI * 1000.0 && s.volume_m3() > 0.99 * 4.0 / 3.0 * PI * 1000.0
    );
    assert!(
        s.surface_area_m2() < 4.0 * PI * 100.0 && s.surface_area_m2() > 0.99 * 4.0 * PI * 100.0
    );
    assert!(norm(s.centre_of_mass_m()) <= 1e-13);
    for g in s.facet_geometry() {
        assert!((norm(g.normal) - 1.0).abs() < 1e-15 && super::dot(g.normal, g.centroid_m) > 0.0);
    }
}

/// Read, check and, if sound, evaluate: whatever the text, an answer and never a panic.
fn survive(text: &str) -> bool {
    let Ok(mesh) = parse_obj(text, "fuzz.obj", 1.0) else {
        return false;
    };
    let Ok(checked) = mesh.check() else {
        return false;
    };
    let poly = Polyhedron::new(checked, 1000.0).unwrap();
    let field = poly.field([1e3, 2e3, 3e3]);
    assert!(field.potential_m2_s2.is_finite());
    let _ = touchdown::shape::facets(&poly, [0.0, 0.0, 1.0], 1e-4);
    true
}

/// Random bytes, random soups of OBJ words (huge and negative numbers, NaN, slashes), and
/// a sound OBJ file cut at every byte: read and checked without a panic (seeded).
#[test]
fn random_and_truncated_input_never_panics() {
    let mut s = Stream(0x9e37_79b9_7f4a_7c15);
    for _ in 0..1500 {
        let bytes: Vec<u8> = (0..s.below(200)).map(|_| s.next() as u8).collect();
        survive(&String::from_utf8_lossy(&bytes));
    }
    let words = [
        "v",
        "f",
        "vn",
        "vt",
        "#",
        "g",
        "1",
        "2",
        "3",
        "4",
        "-1",
        "-2",
        "0",
        "1e308",
        "-1e308",
        "nan",
        "inf",
        "0.5",
        "/",
        "//",
        "1/2/3",
        "-0",
        "4294967296",
        "99999999999999999999",
        "-9223372036854775808",
        "1.",
        ".",
        "-",
        " ",
        "\t",
        "\n",
        "\r\n",
        "\n",
        "\n",
    ];
    for _ in 0..1500 {
        let text: String = (0..s.below(80))
            .map(|_| words[s.below(words.len())])
            .collect::<Vec<_>>()
            .join(" ");
        survive(&text);
    }
    let mesh = cube(1.0);
    let mut obj = String::new();
    for v in &mesh.vertices {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &mesh.facets {
        obj += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    let sound = (0..=obj.len()).filter(|&n| survive(&obj[..n])).count();
    // Only the whole file (and the whole file less its last newline) is a closed surface.
    assert_eq!(sound, 2);
}
