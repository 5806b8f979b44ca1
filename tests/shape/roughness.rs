//! Each facet's roughness (the RMS angle between its normal and its three neighbours') on
//! the regular solids, where every facet has the same closed form, and on icospheres,
//! against the exact angle between two neighbouring facets inscribed in a sphere.
//!
//! The references are computed here from the vertices alone (the test's own adjacency,
//! side lengths, `acos`), never from the mesh module's edges or normals.

use super::{checked, cube, dot, icosphere, norm, sub, twisted_box, uv_sphere};
use std::collections::HashMap;
use touchdown::shape::{Mesh, roughness_deg};

/// Each facet's three edge-neighbours, by the test's own edge map.
fn neighbours(mesh: &Mesh) -> Vec<[usize; 3]> {
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (f, t) in mesh.facets.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            by_edge.entry((a.min(b), a.max(b))).or_default().push(f);
        }
    }
    mesh.facets
        .iter()
        .enumerate()
        .map(|(f, t)| {
            [0, 1, 2].map(|k| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let pair = &by_edge[&(a.min(b), a.max(b))];
                assert_eq!(pair.len(), 2, "a closed, manifold test mesh");
                if pair[0] == f { pair[1] } else { pair[0] }
            })
        })
        .collect()
}

/// Facet `f`'s unit normal from its vertices (counter-clockwise from outside).
fn normal(mesh: &Mesh, f: usize) -> [f64; 3] {
    let [a, b, c] = mesh.facets[f].map(|v| mesh.vertices[v as usize]);
    let (u, v) = (sub(b, a), sub(c, a));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    n.map(|x| x / norm(n))
}

/// The roughness by the definition, with `acos` of the clamped dot product (the function
/// under test uses `atan2(|a x b|, a . b)`).
fn reference_deg(mesh: &Mesh) -> Vec<f64> {
    neighbours(mesh)
        .iter()
        .enumerate()
        .map(|(f, g)| {
            let n = normal(mesh, f);
            let sum: f64 = g
                .iter()
                .map(|&g| {
                    dot(n, normal(mesh, g))
                        .clamp(-1.0, 1.0)
                        .acos()
                        .to_degrees()
                        .powi(2)
                })
                .sum();
            (sum / 3.0).sqrt()
        })
        .collect()
}

/// The regular tetrahedron about the origin, facets counter-clockwise from outside.
fn tetrahedron() -> Mesh {
    Mesh {
        vertices: vec![
            [1.0, 1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
        ],
        facets: vec![[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]],
    }
}

/// Every value within `tolerance` of `expected`; the worst difference.
fn all_near(values: &[f64], expected: f64, tolerance: f64, what: &str) -> f64 {
    let worst = values
        .iter()
        .map(|v| (v - expected).abs())
        .fold(0.0, f64::max);
    assert!(
        values.iter().all(|v| (v - expected).abs() <= tolerance),
        "{what}: worst {worst:.3e} deg from {expected} (tolerance {tolerance:e}): {values:?}"
    );
    worst
}

/// The regular solids: every facet's neighbours meet it at the same angle, 180 deg minus
/// the dihedral angle, so every facet's roughness is that angle (the cube's triangles: one
/// coplanar neighbour and two at 90 deg). The tolerance, 1e-9 deg, is far above the
/// rounding of normals computed from coordinates of order 1 to 1e3 (1e-13 deg) and far
/// below any error of the definition (a wrong neighbour or a missing square root moves
/// these by degrees). The solids are also moved, turned and scaled: the roughness is
/// geometry's alone.
#[test]
fn the_regular_solids_have_their_closed_forms() {
    let tetra = 180.0 - (1.0f64 / 3.0).acos().to_degrees();
    let cube_rms = ((0.0 + 90.0f64.powi(2) + 90.0f64.powi(2)) / 3.0).sqrt();
    let icosa = 180.0 - (-5f64.sqrt() / 3.0).acos().to_degrees();
    // The closed forms as the brief states them, to their four decimals.
    assert!((tetra - 109.4712).abs() < 5e-5 && (cube_rms - 73.4847).abs() < 5e-5);
    assert!((icosa - 41.8103).abs() < 5e-5);
    let turned = |m: Mesh, s: f64, shift: [f64; 3]| -> Mesh {
        let (sa, ca) = 0.7f64.sin_cos();
        let (sb, cb) = 1.9f64.sin_cos();
        let vertices = m
            .vertices
            .iter()
            .map(|p| {
                // About z by 0.7 rad, then about x by 1.9 rad: a rotation, orientation kept.
                let q = [ca * p[0] - sa * p[1], sa * p[0] + ca * p[1], p[2]];
                let r = [q[0], cb * q[1] - sb * q[2], sb * q[1] + cb * q[2]];
                [0, 1, 2].map(|k| s * r[k] + shift[k])
            })
            .collect();
        Mesh { vertices, ..m }
    };
    let mut worst = 0.0_f64;
    for (name, mesh, expected) in [
        ("tetrahedron", tetrahedron(), tetra),
        ("cube", cube(1.0), cube_rms),
        ("icosahedron", icosphere(1.0, 0), icosa),
        (
            "tetrahedron turned",
            turned(tetrahedron(), 37.0, [1e3, -2e3, 5e2]),
            tetra,
        ),
        (
            "cube turned",
            turned(cube(2.5), 0.01, [-3.0, 0.0, 7.0]),
            cube_rms,
        ),
        (
            "icosahedron turned",
            turned(icosphere(1.0, 0), 250.0, [0.0, 1e3, 0.0]),
            icosa,
        ),
    ] {
        let count = mesh.facets.len();
        let r = roughness_deg(&checked(mesh));
        assert_eq!(r.len(), count, "{name}: one value per facet");
        worst = worst.max(all_near(&r, expected, 1e-9, name));
    }
    eprintln!("regular solids: worst {worst:.3e} deg (tolerance 1e-9)");
}

/// The angle between the normals of two facets inscribed in a sphere of radius `r` that
/// share an edge of length `e`, `cot_f` and `cot_g` the cotangents of the angles opposite
/// the edge in each, rad. A plane through three points of a sphere has its normal through
/// the sphere's centre `O` and the triangle's circumcentre `C`; the circumcentre lies at
/// the signed distance `d = (e / 2) cot A` from the edge's midpoint `M` (negative for an
/// obtuse `A`), and `O C` is perpendicular to `M C`, so the normal leans `asin(d / |OM|)`
/// from `OM` towards the facet, `|OM| = sqrt(r^2 - e^2 / 4)`. The two facets lean to either
/// side: the angle between the normals is the sum (its absolute value where the edge is
/// concave).
fn inscribed_angle(r: f64, e: f64, cot_f: f64, cot_g: f64) -> f64 {
    let om = (r * r - e * e / 4.0).sqrt();
    let lean = |cot: f64| (e / 2.0 * cot / om).asin();
    (lean(cot_f) + lean(cot_g)).abs()
}

/// The cotangent of facet `f`'s angle at its vertex `k` (opposite the edge `k+1, k+2`),
/// from its side lengths (law of cosines).
fn cot_at(mesh: &Mesh, f: usize, k: usize) -> f64 {
    let t = mesh.facets[f];
    let p = |i: usize| mesh.vertices[t[(k + i) % 3] as usize];
    let (b, c, a) = (
        norm(sub(p(1), p(0))),
        norm(sub(p(2), p(0))),
        norm(sub(p(2), p(1))),
    );
    let cos = (b * b + c * c - a * a) / (2.0 * b * c);
    cos / (1.0 - cos * cos).sqrt()
}

/// Icospheres of 1,280, 5,120 and 20,480 facets: every facet's roughness against the exact
/// angles of `inscribed_angle`, from side lengths only. The vertices lie on the sphere to
/// the rounding of their coordinates (1e-16 relative), which moves a normal by about
/// `1e-16 R / e` rad, 1e-13 deg for the smallest facets here; the tolerance, 1e-9 deg, is
/// far above that and far below what a wrong neighbour, a wrong mean or a wrong unit would
/// do (the mean roughness is 1.3 to 5 deg here).
///
/// Then the scale: a facet of side `e` on a sphere of radius `R` sees its neighbours'
/// normals at about `e / (sqrt(3) R)` rad (equilateral triangles; `2 d = e / sqrt(3)` is the
/// distance between their circumcentres). The area-weighted mean roughness in units of
/// `e / (sqrt(3) R)`, `e` the mean edge, is printed (1.013, 1.012, 1.012), and halving the
/// edge halves the mean roughness: the ratio between successive levels is within 2 % of
/// the ratio of their mean edge lengths. What separates them is the curvature (`|OM| = R
/// sqrt(1 - e^2 / 4 R^2)` and the `asin`, relative `e^2 / 8 R^2` = 2e-3 at 1,280 facets and
/// four times less at each level) and the change of the triangles' shapes from one level to
/// the next, which is not bounded here but measured with the rest: 0.09 % and 0.02 %.
#[test]
fn an_icospheres_roughness_is_the_inscribed_closed_form() {
    let radius = 1_000.0;
    let mut worst = 0.0_f64;
    let mut levels = Vec::new();
    for level in [3, 4, 5] {
        let mesh = icosphere(radius, level);
        let near = neighbours(&mesh);
        let r = roughness_deg(&checked(mesh.clone()));
        assert_eq!(r.len(), mesh.facets.len());
        let (mut area_sum, mut weighted, mut edges) = (0.0, 0.0, 0.0);
        for (f, g) in near.iter().enumerate() {
            let t = mesh.facets[f];
            let mut squares = 0.0;
            for (k, &g) in g.iter().enumerate() {
                // Edge k runs from corner k to k+1: opposite corner k+2 in f.
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let u = mesh.facets[g];
                let opposite = (0..3).find(|&j| u[j] != a && u[j] != b).unwrap();
                let e = norm(sub(mesh.vertices[a as usize], mesh.vertices[b as usize]));
                let angle = inscribed_angle(
                    radius,
                    e,
                    cot_at(&mesh, f, (k + 2) % 3),
                    cot_at(&mesh, g, opposite),
                );
                squares += angle.to_degrees().powi(2);
                edges += e / 3.0;
            }
            let expected = (squares / 3.0).sqrt();
            let miss = (r[f] - expected).abs();
            worst = worst.max(miss);
            assert!(
                miss <= 1e-9,
                "level {level}, facet {f}: {} deg against {expected} deg",
                r[f]
            );
            let [p, q, s] = t.map(|v| mesh.vertices[v as usize]);
            let (u, v) = (sub(q, p), sub(s, p));
            let area = 0.5
                * norm([
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ]);
            area_sum += area;
            weighted += area * r[f];
        }
        let mean_deg = weighted / area_sum;
        let mean_edge = edges / mesh.facets.len() as f64;
        let scale_deg = (mean_edge / (3f64.sqrt() * radius)).to_degrees();
        eprintln!(
            "icosphere level {level}: mean roughness {mean_deg:.4} deg by area, {:.4} e / \
             (sqrt(3) R)",
            mean_deg / scale_deg
        );
        levels.push((mean_deg, mean_edge));
    }
    for w in levels.windows(2) {
        let (roughness, edge) = (w[0].0 / w[1].0, w[0].1 / w[1].1);
        eprintln!("icosphere: roughness ratio {roughness:.4}, edge ratio {edge:.4}");
        assert!(
            (roughness / edge - 1.0).abs() < 0.02,
            "the mean roughness halves as the edge does: {roughness} against {edge}"
        );
    }
    eprintln!("icosphere: worst {worst:.3e} deg (tolerance 1e-9)");
}

/// Any checked mesh, convex or not: the function against the definition computed with
/// `acos` and the test's own adjacency (a twisted, tapered, shifted box whose side quads are
/// not planar, and a latitude-longitude sphere with its thin polar triangles). The
/// tolerance, 1e-6 deg, is `acos`'s own rounding near 0 deg (`sqrt(2 eps)` rad, 1.2e-6 deg
/// for one angle, far less in the root mean square of three); every value is finite and in
/// [0, 180].
#[test]
fn any_mesh_matches_the_definition() {
    let mut worst = 0.0_f64;
    for (name, mesh) in [
        (
            "twisted box",
            twisted_box(3.0, 2.0, 1.0, 35.0, 0.6, [10.0, -4.0, 2.0]),
        ),
        ("uv sphere", uv_sphere(500.0, 24, 48)),
    ] {
        let expected = reference_deg(&mesh);
        let r = roughness_deg(&checked(mesh));
        assert_eq!(r.len(), expected.len());
        for (f, (v, e)) in r.iter().zip(&expected).enumerate() {
            assert!(
                v.is_finite() && (0.0..=180.0).contains(v),
                "{name} {f}: {v}"
            );
            worst = worst.max((v - e).abs());
            assert!((v - e).abs() <= 1e-6, "{name} facet {f}: {v} against {e}");
        }
    }
    eprintln!("any mesh: worst {worst:.3e} deg from acos (tolerance 1e-6)");
}
