//! The facets' attraction by the tree (`shape::FacetTree`) against the exact sum of Werner
//! and Scheeres, and a triaxial ellipsoid's facets against the homogeneous ellipsoid's
//! closed form (Carlson's `R_D`).

use super::{checked, icosphere, norm, sub, twisted_box};
use std::f64::consts::PI;
use touchdown::shape::{
    CheckedMesh, FacetTree, G, GravitySum, Mesh, OPENING, Polyhedron, facets_told, slope_deg,
};

const RHO: f64 = 2500.0;

/// The icosphere of `levels` subdivisions stretched to the ellipsoid of semi-axes `axes`
/// (m): every vertex on the ellipsoid.
pub fn ellipsoid(axes: [f64; 3], levels: u32) -> Mesh {
    let mut mesh = icosphere(1.0, levels);
    for v in &mut mesh.vertices {
        *v = std::array::from_fn(|k| v[k] * axes[k]);
    }
    mesh
}

/// Carlson's symmetric elliptic integral of the second kind, `R_D(x, y, z) = 3/2 int_0^inf
/// dt / ((t + z) sqrt((t + x)(t + y)(t + z)))`, by duplication (Carlson 1995, Numer.
/// Algorithms 10, 13-26), to about 1e-15 relative: the series' remainder after the fifth
/// order is below `3 r^6` for `r` the largest relative spread, taken below 1e-3 here.
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    let (mut x, mut y, mut z) = (x, y, z);
    let mut sum = 0.0;
    let mut factor = 1.0;
    loop {
        let mean = (x + y + 3.0 * z) / 5.0;
        let spread = [x, y, z]
            .iter()
            .map(|v| ((mean - v) / mean).abs())
            .fold(0.0, f64::max);
        if spread < 1e-3 {
            let dx = (mean - x) / mean;
            let dy = (mean - y) / mean;
            let dz = (mean - z) / mean;
            let ea = dx * dy;
            let eb = dz * dz;
            let ec = ea - eb;
            let ed = ea - 6.0 * eb;
            let ee = ed + ec + ec;
            let series = 1.0
                + ed * (-3.0 / 14.0 + 9.0 / 88.0 * ed - 9.0 / 52.0 * dz * ee)
                + dz * (ee / 6.0 + dz * (-9.0 / 22.0 * ec + dz * 3.0 / 26.0 * ea));
            return 3.0 * sum + factor * series / (mean * mean.sqrt());
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        sum += factor / (sz * (z + lambda));
        factor *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// The attraction of the homogeneous ellipsoid of semi-axes `axes` at a point `r` inside
/// it or on it: `g_i = -2 pi G rho A_i r_i`, `A_i = (2/3) a b c R_D(a_j^2, a_k^2, a_i^2)`
/// (the sum of the three `A_i` is 2, the sphere's `A = 2/3`).
pub fn ellipsoid_attraction(axes: [f64; 3], rho: f64, r: [f64; 3]) -> [f64; 3] {
    let [a, b, c] = axes;
    let sq = axes.map(|x| x * x);
    std::array::from_fn(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let coefficient = 2.0 / 3.0 * a * b * c * carlson_rd(sq[j], sq[k], sq[i]);
        -2.0 * PI * G * rho * coefficient * r[i]
    })
}

/// The largest error of the tree's attraction at each of `openings` against the exact sum,
/// relative to each facet's attraction, over every facet of `mesh`.
fn tree_errors(mesh: &CheckedMesh, openings: &[f64]) -> Vec<f64> {
    let poly = Polyhedron::new(mesh.clone(), RHO).unwrap();
    let count = mesh.facet_geometry().len();
    let exact: Vec<[f64; 3]> = (0..count)
        .map(|f| poly.field_on_facet(f).acceleration_m_s2)
        .collect();
    let g_rho = G * RHO;
    openings
        .iter()
        .map(|&opening| {
            let sums = FacetTree::new(mesh, opening).sums(|_| {});
            sums.iter()
                .zip(&exact)
                .map(|(s, e)| norm(sub(s.map(|x| -g_rho * x), *e)) / norm(*e))
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Summed exactly (opening 0) the tree regroups the exact sum facet by facet: the same
/// terms, each edge's logarithm taken once for each of its two facets, so the two agree to
/// rounding: the terms are of the size of the attraction, and a sum of `F` of them rounds to
/// about `F eps` of it (1e-12 at 1,280 facets; 1e-11 allowed).
#[test]
fn summed_exactly_the_tree_is_the_polyhedron() {
    for mesh in [
        icosphere(100.0, 3),
        ellipsoid([300.0, 200.0, 125.0], 3),
        twisted_box(30.0, 20.0, 10.0, 25.0, 0.7, [3.0, -2.0, 1.0]),
    ] {
        let error = tree_errors(&checked(mesh), &[0.0])[0];
        assert!(error < 1e-11, "error {error:e}");
    }
}

/// A mesh of at most [`touchdown::shape::LEAF`] facets is one leaf, summed facet by facet
/// at any opening: the exact sum to rounding (as above). And the sums are the same bits on
/// one thread and on four: each point's terms are added in one order whatever thread takes
/// its leaf.
#[test]
fn a_small_mesh_is_summed_exactly_and_threads_do_not_change_a_bit() {
    let cube = checked(twisted_box(10.0, 10.0, 10.0, 0.0, 1.0, [0.0; 3]));
    assert!(tree_errors(&cube, &[OPENING])[0] < 1e-12);
    let mesh = checked(ellipsoid([300.0, 200.0, 125.0], 4));
    let tree = FacetTree::new(&mesh, OPENING);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| tree.sums(|_| {}))
    };
    let (one, four) = (on(1), on(4));
    assert_eq!(one.len(), 5_120);
    assert!(
        one.iter()
            .zip(&four)
            .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits))
    );
}

/// Opened at the default angle, the tree's attraction is within 5e-5 of the exact sum's at
/// every facet, on a sphere, a triaxial ellipsoid and a body with a deep waist (5,120
/// facets each). The first term the expansion leaves out is of the size `OPENING^6 = 4e-3`
/// of a far group's own terms, and the groups' terms add up to a few times the attraction;
/// measured: 1.0e-5 (sphere), 1.3e-5 (ellipsoid), 3.1e-5 (the waisted body) here, and
/// 2.7e-5 on the ellipsoid of 1.3 million facets (README); at 0.8, 1.8e-3 to 2.7e-3.
/// Opened wider, at 0.8, the error grows (about `(0.8 / 0.4)^6` more for the worst groups):
/// a tree that ignored the angle, or a wrong term of the expansion, would not meet both.
#[test]
fn opened_at_the_default_angle_the_tree_is_within_its_bound() {
    let bodies = [
        ("sphere", icosphere(250.0, 4)),
        ("ellipsoid", ellipsoid([300.0, 200.0, 125.0], 4)),
        ("peanut", peanut(4)),
    ];
    for (name, mesh) in bodies {
        let errors = tree_errors(&checked(mesh), &[OPENING, 0.8]);
        let (at_default, wide) = (errors[0], errors[1]);
        assert!(at_default < 5e-5, "{name}: {at_default:e}");
        assert!(
            wide > 4.0 * at_default,
            "{name}: {wide:e} against {at_default:e}"
        );
    }
}

/// Two ellipsoids' halves joined by a waist: the icosphere pushed in around its equator
/// and stretched, so that facets of one lobe see the other's across the waist.
fn peanut(levels: u32) -> Mesh {
    let mut mesh = icosphere(1.0, levels);
    for v in &mut mesh.vertices {
        let [x, y, z] = *v;
        let waist = 1.0 - 0.5 * (-(x * x) / 0.1).exp();
        *v = [400.0 * x, 180.0 * y * waist, 150.0 * z * waist];
    }
    mesh
}

/// A triaxial ellipsoid of 600 x 400 x 250 m (semi-axes 300, 200, 125 m), 2,500 kg/m^3,
/// spinning once in 6 h about `z`, meshed with 20,480 facets (the icosphere of 5 levels
/// stretched): every facet's effective gravity, by the tree, within 0.1 % of the
/// homogeneous ellipsoid's closed form at its centroid, and its slope (against its own
/// normal) within 0.05 deg. The polyhedron lies inside the ellipsoid by the facets'
/// sagitta, about 2e-4 of the radius here, and the shell left out pulls by about that
/// fraction times `ln(R / s)`: the bound has a factor 3 to spare (measured: 0.033 %, and
/// 0.0062 deg; the exact sum 0.033 % and 0.0060 deg; 1.3 million facets: README).
#[test]
fn a_triaxial_ellipsoid_s_facets_follow_the_closed_form() {
    let axes = [300.0, 200.0, 125.0];
    let mesh = checked(ellipsoid(axes, 5));
    let poly = Polyhedron::new(mesh, RHO).unwrap();
    let omega = 2.0 * PI / (6.0 * 3600.0);
    let facets = facets_told(
        &poly,
        [0.0, 0.0, 1.0],
        omega,
        GravitySum::Tree { opening: OPENING },
        |_| {},
    );
    let (mut worst_g, mut worst_slope) = (0.0_f64, 0.0_f64);
    for f in &facets {
        let c = f.centroid_m;
        let closed = ellipsoid_attraction(axes, RHO, c);
        let spin = [omega * omega * c[0], omega * omega * c[1], 0.0];
        let effective = std::array::from_fn(|k| closed[k] + spin[k]);
        worst_g = worst_g.max(norm(sub(f.effective_m_s2, effective)) / norm(effective));
        worst_slope = worst_slope.max((f.slope_deg - slope_deg(f.normal, effective)).abs());
    }
    assert!(worst_g < 1e-3, "{worst_g:e}");
    assert!(worst_slope < 0.05, "{worst_slope} deg");
}

/// The closed form itself: a sphere's `A_i` are 2/3 (`R_D(x, x, x) = x^(-3/2)`), the three
/// `A_i` of any ellipsoid sum to 2, and `R_D(0, 2, 1) = 1.7972103521034` (Carlson 1995,
/// table 4, to the digits given there).
#[test]
fn carlson_s_integral_matches_its_known_values() {
    for x in [0.3_f64, 1.0, 7.0] {
        let rd = carlson_rd(x, x, x);
        assert!((rd * x.powf(1.5) - 1.0).abs() < 1e-14, "{rd}");
    }
    assert!((carlson_rd(0.0, 2.0, 1.0) - 1.797_210_352_103_4).abs() < 1e-12);
    let [a, b, c] = [300.0_f64, 200.0, 125.0];
    let sum = 2.0 / 3.0
        * a
        * b
        * c
        * (carlson_rd(b * b, c * c, a * a)
            + carlson_rd(c * c, a * a, b * b)
            + carlson_rd(a * a, b * b, c * c));
    assert!((sum - 2.0).abs() < 1e-13, "{sum}");
}
