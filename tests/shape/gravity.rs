//! The polyhedron's gravity against closed forms: a sphere's `G M / r^2`, the Laplacian
//! inside and outside, a far-away point mass, the gradient of the potential, and the value
//! on a facet against its limit from outside.

use super::{checked, cube, icosphere, norm, sagitta_m, scale, sub, twisted_box, unit};
use std::f64::consts::PI;
use touchdown::shape::{G, Polyhedron};

const RHO: f64 = 2000.0;

/// Directions that no symmetry of the icosphere or the box singles out.
fn directions() -> Vec<[f64; 3]> {
    [
        [1.0, 2.0, 3.0],
        [-0.3, 0.1, 0.9],
        [0.7, -0.7, 0.1],
        [-0.2, -0.5, -0.8],
    ]
    .map(unit)
    .to_vec()
}

/// The error bound of the icosphere's attraction at a point at radius `p` (m) against that
/// of a uniform sphere, from the material between the sphere and the facets: a layer no
/// thicker than the sagitta `s` under the sphere of radius `R`. Its attraction is at most
/// that of the whole layer taken with absolute values, `G rho int dV / d^2`; over a sphere
/// of radius `a`, `int dA / d^2 = 2 pi (a / p) ln((a + p) / |a - p|)`, and over the layer's
/// depth `int ln(2 R / |a - p|) da <= s (1 + ln(2 / s))` for any `p`, so
/// `|g_layer| <= 2 pi G rho (R / p) s (1 + ln(4 R / s))`. Outside the sphere the layer's
/// monopole `G M_layer / p^2` is part of the difference too (the test uses the
/// polyhedron's own mass), and the multipoles of the layer bound it more tightly far off:
/// the icosphere keeps the icosahedron's symmetry, which has no harmonics of degree 1 to 5,
/// so `|g_layer - G M_layer / p^2| <= G M_layer sum_{l >= 6} (l + 1) (R / p)^l / p^2`.
fn sphere_bound(radius: f64, sagitta: f64, layer_mass: f64, p: f64) -> f64 {
    let near = 2.0 * PI * G * RHO * (radius / p) * sagitta * (1.0 + (4.0 * radius / sagitta).ln())
        + G * layer_mass / (p * p);
    if p <= radius {
        return near;
    }
    let x = radius / p;
    let series =
        1.0 / (1.0 - x).powi(2) - (0..6).map(|l| f64::from(l + 1) * x.powi(l)).sum::<f64>();
    near.min(G * layer_mass * series / (p * p))
}

#[test]
fn a_sphere_attracts_as_its_mass_at_its_centre() {
    for radius in [100.0, 1000.0] {
        let mesh = checked(icosphere(radius, 4));
        let s = sagitta_m(&mesh, radius);
        let poly = Polyhedron::new(mesh, RHO).unwrap();
        let mass = poly.mass_kg();
        let layer_mass = RHO * 4.0 / 3.0 * PI * radius.powi(3) - mass;
        assert!(layer_mass > 0.0 && s > 0.0 && s < 2e-3 * radius, "s = {s}");
        for factor in [1.01, 1.5, 3.0] {
            for d in directions() {
                let r = factor * radius;
                let a = poly.acceleration(scale(d, r));
                let expected = scale(d, -G * mass / (r * r));
                let error = norm(sub(a, expected));
                let bound = sphere_bound(radius, s, layer_mass, r);
                assert!(
                    error <= bound,
                    "R {radius} m, r {factor} R: error {error:.3e} m/s^2 above {bound:.3e} \
                     (g {:.6e})",
                    norm(expected)
                );
            }
        }
        // On the surface, at facet centroids (a sample): the uniform sphere's attraction
        // at radius p inside it is 4/3 pi G rho p; the same layer bound holds.
        let count = poly.mesh().facet_geometry().len();
        for f in (0..count).step_by(97) {
            let c = poly.mesh().facet_geometry()[f].centroid_m;
            let p = norm(c);
            let a = poly.field_on_facet(f).acceleration_m_s2;
            let expected = scale(unit(c), -4.0 / 3.0 * PI * G * RHO * p);
            let error = norm(sub(a, expected));
            let bound = sphere_bound(radius, s, 0.0, p);
            assert!(
                error <= bound,
                "R {radius}, facet {f}: {error:.3e} above {bound:.3e}"
            );
        }
    }
}

/// The sum of the facets' solid angles is 4 pi inside and 0 outside. Each is computed to a
/// few roundings of 2 pi (an `atan2` of rounded arguments), and the sum of `n` of them adds
/// `n` roundings: `4 n eps` relative to `4 pi G rho`. Near the surface the inputs' rounding
/// counts too: `r_i = v_i - r` is rounded to `eps |r|`, and a facet's solid angle turns at
/// up to `1 / delta` per metre at a distance `delta` from its edges: `4 eps size / delta`
/// more, with `delta` at least the point's clearance from the surface, listed with it.
/// Within 1e-13 of 4 pi G rho far from the surface, 2e-10 at 1e-4 m from a cube's face.
#[test]
fn the_laplacian_is_minus_four_pi_g_rho_inside_and_zero_outside() {
    let inside_value = -4.0 * PI * G * RHO;
    let cube_poly = Polyhedron::new(checked(cube(10.0)), RHO).unwrap();
    let sphere_poly = Polyhedron::new(checked(icosphere(100.0, 4)), RHO).unwrap();
    let v0 = sphere_poly.mesh().mesh().vertices[7];
    let f0 = sphere_poly.mesh().facet_geometry()[123];
    type Points = Vec<([f64; 3], f64)>;
    let cases: [(&Polyhedron, Points, Points); 2] = [
        (
            &cube_poly,
            vec![
                ([0.0; 3], 10.0),
                ([3.0, -2.0, 9.9999], 1e-4),
                ([9.99, 9.99, 9.99], 1e-2),
                ([-9.9, 9.999, -5.0], 1e-3),
            ],
            vec![
                ([10.01, 2.0, 3.0], 1e-2),
                ([10.001, 10.001, 10.001], 1e-3),
                ([50.0, -30.0, 20.0], 40.0),
                ([0.0, 0.0, -10.0001], 1e-4),
            ],
        ),
        (
            &sphere_poly,
            vec![
                ([0.0; 3], 99.0),
                (scale(v0, 0.9999), 5e-3),
                ([30.0, -40.0, 70.0], 10.0),
                (sub(f0.centroid_m, scale(f0.normal, 1e-4)), 1e-4),
            ],
            vec![
                (scale(v0, 1.0001), 5e-3),
                ([300.0, 10.0, -5.0], 200.0),
                (scale(f0.centroid_m, 1.0 + 1e-6), 5e-5),
                ([0.0, 0.0, 100.5], 0.4),
            ],
        ),
    ];
    for (poly, inside, outside) in cases {
        let n = poly.mesh().facet_geometry().len() as f64;
        let size = poly.mesh().size_m();
        let tolerance =
            |clearance: f64| 4.0 * f64::EPSILON * (n + size / clearance) * inside_value.abs();
        for (r, clearance) in inside {
            let l = poly.laplacian(r);
            let t = tolerance(clearance);
            assert!(
                (l - inside_value).abs() <= t,
                "inside {r:?}: {l:e} against {inside_value:e}"
            );
        }
        for (r, clearance) in outside {
            let l = poly.laplacian(r);
            assert!(
                l.abs() <= tolerance(clearance),
                "outside {r:?}: {l:e} against 0"
            );
        }
    }
}

/// Far away, any body attracts as its mass at its centre of mass: the multipoles of a mass
/// within `L` of its centre of mass add at most `sum_{l >= 2} (l + 1) (L / d)^l` of `G M /
/// d^2` (the dipole is zero about the centre of mass), `3 (L/d)^2` to leading order. The sums
/// of edge and facet terms cancel down to the result by `(d / L)^2`, so rounding adds about
/// `(d / L)^2` roundings of the terms, `1e-9` relative at 1000 `L`. The box is twisted,
/// tapered and shifted off the origin, so a wrong centre of mass (a dipole, `~3 |offset| /
/// d`) fails.
#[test]
fn far_away_it_attracts_as_a_point_mass() {
    let mesh = checked(twisted_box(30.0, 12.0, 7.0, 35.0, 0.6, [40.0, -25.0, 10.0]));
    let poly = Polyhedron::new(mesh, RHO).unwrap();
    let com = poly.centre_of_mass_m();
    let reach = poly
        .mesh()
        .mesh()
        .vertices
        .iter()
        .map(|&v| norm(sub(v, com)))
        .fold(0.0, f64::max);
    let mass = poly.mass_kg();
    for factor in [100.0, 1000.0] {
        let d = factor * reach;
        let x = reach / d;
        let relative =
            1.0 / (1.0 - x).powi(2) - 1.0 - 2.0 * x + 1e3 * f64::EPSILON * factor * factor;
        for dir in directions() {
            let r = [
                com[0] + d * dir[0],
                com[1] + d * dir[1],
                com[2] + d * dir[2],
            ];
            let a = poly.acceleration(r);
            let g = G * mass / (d * d);
            let error = norm(sub(a, scale(dir, -g))) / g;
            assert!(
                error <= relative,
                "{factor} L: relative error {error:.3e} above {relative:.3e}"
            );
            let u = poly.potential(r);
            let error = (u + G * mass / d).abs() / (G * mass / d);
            assert!(
                error <= relative,
                "{factor} L: potential off by {error:.3e}"
            );
        }
    }
}

/// The attraction is minus the gradient of the potential: central differences of step
/// `h = 1e-5 L` err by `h^2 / 6` times the third derivatives, below `(h / d)^2 = 1e-9` of
/// the attraction at points `d >= 0.2 L` from the surface, and by the potential's
/// rounding over `h`, `~10 eps U / h`, below `1e-9` of it: 1e-6 leaves room for both.
#[test]
fn the_attraction_is_minus_the_gradient_of_the_potential() {
    let poly = Polyhedron::new(
        checked(twisted_box(30.0, 12.0, 7.0, 35.0, 0.6, [0.0; 3])),
        RHO,
    )
    .unwrap();
    let h = 1e-5 * 30.0;
    let points = [
        [0.0, 0.0, 0.0],
        [5.0, 2.0, -1.0],
        [45.0, 10.0, 8.0],
        [-20.0, -30.0, 25.0],
        [0.0, 0.0, 60.0],
    ];
    for r in points {
        let a = poly.acceleration(r);
        let gradient: [f64; 3] = std::array::from_fn(|k| {
            let mut plus = r;
            let mut minus = r;
            plus[k] += h;
            minus[k] -= h;
            (poly.potential(plus) - poly.potential(minus)) / (2.0 * h)
        });
        let error = norm([a[0] + gradient[0], a[1] + gradient[1], a[2] + gradient[2]]) / norm(a);
        assert!(
            error <= 1e-6,
            "at {r:?}: {a:?} against -grad {gradient:?} ({error:.2e})"
        );
    }
}

/// On a facet, the gravity is taken at its centroid with the facet's own (undefined) solid
/// angle left out; it must be the limit of points approaching from outside along the
/// normal. The attraction is continuous across a facet and its gradient bounded near the
/// centroid: `4 pi G rho` (its jump across the facet) plus the facet's own edges'
/// logarithms, `2 G rho ln(e / delta)` each at a distance `delta` from an edge of length
/// `e` (under 3 here), so it changes by at most `h 20 G rho` over a height `h` above it, plus
/// the rounding of sums that cancel (1e-12 of the attraction).
#[test]
fn on_a_facet_the_gravity_is_its_limit_from_outside() {
    let cases = [
        Polyhedron::new(
            checked(twisted_box(30.0, 12.0, 7.0, 35.0, 0.6, [4.0, -2.0, 1.0])),
            RHO,
        )
        .unwrap(),
        Polyhedron::new(checked(icosphere(100.0, 3)), RHO).unwrap(),
    ];
    for poly in &cases {
        let geometry = poly.mesh().facet_geometry();
        for f in (0..geometry.len()).step_by(7) {
            let g = geometry[f];
            let on = poly.field_on_facet(f);
            let size = g.area_m2.sqrt();
            for step in [1e-3, 1e-5, 1e-7] {
                let h = step * size;
                let near = poly.field([0, 1, 2].map(|k| g.centroid_m[k] + h * g.normal[k]));
                let a = norm(on.acceleration_m_s2);
                let error = norm(sub(near.acceleration_m_s2, on.acceleration_m_s2));
                let bound = 20.0 * G * RHO * h + 1e-12 * a;
                assert!(
                    error <= bound,
                    "facet {f}, h {h:e}: {error:.3e} above {bound:.3e}"
                );
                let error = (near.potential_m2_s2 - on.potential_m2_s2).abs();
                assert!(
                    error <= a * h * 1.01 + 1e-12 * on.potential_m2_s2.abs(),
                    "potential {error:e}"
                );
                assert!(
                    near.laplacian_s2.abs() <= 1e-9 * G * RHO,
                    "outside: {:e}",
                    near.laplacian_s2
                );
            }
            assert!(
                on.laplacian_s2.abs() <= 1e-9 * G * RHO,
                "on, from outside: {:e}",
                on.laplacian_s2
            );
        }
    }
}
