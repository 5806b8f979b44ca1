//! Slopes on a spinning sphere against the closed form, the centrifugal acceleration, and
//! every facet at once.

use super::{checked, cross, dot, icosphere, norm, scale, sub, unit, uv_sphere};
use std::f64::consts::PI;
use touchdown::shape::{
    FacetGravity, G, Polyhedron, centrifugal, facet_gravity, facets, latitude_longitude, slope_deg,
    spin_frame, unit_axis,
};

const RHO: f64 = 2000.0;
const RADIUS: f64 = 1000.0;
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// The slope at geocentric latitude `lat_deg` on a sphere of surface gravity `g` spinning
/// about its polar axis with `w^2 R = w2r`: the centrifugal acceleration `w^2 R cos(phi)`
/// has `w^2 R cos^2(phi)` against gravity and `w^2 R cos(phi) sin(phi)` along the surface
/// towards the equator, so `slope = atan(w^2 R cos sin / (g - w^2 R cos^2))` (atan2: above
/// 90 deg where the spin wins).
fn closed_form_deg(g: f64, w2r: f64, lat_deg: f64) -> f64 {
    let (s, c) = lat_deg.to_radians().sin_cos();
    (w2r * c * s).atan2(g - w2r * c * c).to_degrees()
}

/// The largest slope change, deg, an error `delta` in the attraction can make where the
/// effective gravity is `effective`: turning a vector of length `|g|` by adding `delta`
/// turns it by at most `asin(|delta| / |g|)`.
fn turn_deg(delta: f64, effective: f64) -> f64 {
    (delta / effective).min(1.0).asin().to_degrees()
}

/// The spin rates of the tests: `w^2 R` a small share of the surface gravity, half of it
/// (near the critical spin), and twice it (faster than critical: the equator's effective
/// gravity points away from the surface, slopes above 90 deg).
const SPIN_SHARES: [f64; 3] = [0.02, 0.5, 2.0];

/// Points on the sphere itself (outside the icosphere's facets) with the sphere's radial
/// normal: the slope the polyhedron's attraction gives there against the closed form.
/// The tolerance is the turn the attraction's own error can make (that error, measured
/// against `G M / R^2` here, is bounded in `a_sphere_attracts_as_its_mass_at_its_centre`):
/// what remains tested is the centrifugal term and the slope's definition.
#[test]
fn a_spinning_sphere_slopes_as_the_closed_form_says() {
    let poly = Polyhedron::new(checked(icosphere(RADIUS, 4)), RHO).unwrap();
    let g = G * poly.mass_kg() / (RADIUS * RADIUS);
    for share in SPIN_SHARES {
        let omega = (share * g / RADIUS).sqrt();
        for lat in [0.0, 15.0, 30.0, 45.0, 60.0, 75.0] {
            let (sl, cl) = f64::to_radians(lat).sin_cos();
            let (so, co) = 37f64.to_radians().sin_cos();
            let up = [cl * co, cl * so, sl];
            let p = scale(up, RADIUS);
            let attraction = poly.acceleration(p);
            let exact = scale(up, -g);
            let effective = add(attraction, centrifugal(Z, omega, p));
            let exact_effective = norm(add(exact, centrifugal(Z, omega, p)));
            let slope = slope_deg(up, effective);
            let expected = closed_form_deg(g, share * g, lat);
            let tolerance = turn_deg(norm(sub(attraction, exact)), exact_effective) + 1e-9;
            assert!(
                (slope - expected).abs() <= tolerance,
                "w^2 R = {share} g, latitude {lat}: slope {slope} deg against {expected} \
                 (tolerance {tolerance:.2e})"
            );
        }
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// The tilt of a facet's normal from the radial direction through its centroid, deg.
fn tilt_deg(f: &FacetGravity) -> f64 {
    dot(f.normal, unit(f.centroid_m))
        .min(1.0)
        .acos()
        .to_degrees()
}

/// The same on the icosphere's own facets, as `facet_gravity` computes them (attraction
/// at the centroid, the facet's normal): the facet nearest each latitude with the normal
/// closest to radial. Expected: the closed form at the centroid's latitude and radius
/// `p`, where the uniform sphere attracts with `4/3 pi G rho p`. Tolerance: the normal's
/// tilt from radial (the slope is measured from the facet's normal) plus the turn of the
/// attraction's error at the centroid. Without spin every slope is within the same bound
/// of 0.
///
/// The latitudes are about the spin axis, so a spin about a tilted axis slopes the sphere as
/// the closed form says at the latitude about that axis (a latitude about the mesh's `z`
/// would miss it by up to the tilt).
#[test]
fn the_icosphere_facets_slope_as_the_closed_form_says() {
    let poly = Polyhedron::new(checked(icosphere(RADIUS, 4)), RHO).unwrap();
    let count = poly.mesh().facet_geometry().len();
    for axis in [Z, unit_axis([1.0, 2.0, 3.0]).unwrap()] {
        slopes_about(&poly, count, axis);
    }
}

/// `the_icosphere_facets_slope_as_the_closed_form_says` about the spin axis `axis`.
fn slopes_about(poly: &Polyhedron, count: usize, axis: [f64; 3]) {
    let all: Vec<FacetGravity> = (0..count)
        .map(|f| facet_gravity(poly, f, axis, 0.0))
        .collect();
    let g0 = G * poly.mass_kg() / (RADIUS * RADIUS);
    for share in SPIN_SHARES {
        let omega = (share * g0 / RADIUS).sqrt();
        for lat in [0.0, 15.0, 30.0, 45.0, 60.0, 75.0] {
            let f = (0..count)
                .filter(|&f| (all[f].latitude_deg - lat).abs() < 2.0)
                .min_by(|&a, &b| tilt_deg(&all[a]).total_cmp(&tilt_deg(&all[b])))
                .unwrap();
            let site = facet_gravity(poly, f, axis, omega);
            let p = norm(site.centroid_m);
            let g = 4.0 / 3.0 * PI * G * RHO * p;
            let exact = scale(unit(site.centroid_m), -g);
            let exact_effective = norm(add(exact, centrifugal(axis, omega, site.centroid_m)));
            let expected = closed_form_deg(g, omega * omega * p, site.latitude_deg);
            let tolerance = tilt_deg(&site)
                + turn_deg(norm(sub(site.gravity_m_s2, exact)), exact_effective)
                + 1e-9;
            assert!(
                (site.slope_deg - expected).abs() <= tolerance,
                "axis {axis:?}, w^2 R = {share} g, facet {f} at latitude {}: slope {} against \
                 {expected} (tolerance {tolerance:.3e})",
                site.latitude_deg,
                site.slope_deg
            );
            assert_eq!(site.effective_magnitude_m_s2, norm(site.effective_m_s2));
        }
    }
    for site in all.iter().step_by(13) {
        let g = 4.0 / 3.0 * PI * G * RHO * norm(site.centroid_m);
        let tolerance = tilt_deg(site)
            + turn_deg(
                norm(sub(site.gravity_m_s2, scale(unit(site.centroid_m), -g))),
                g,
            )
            + 1e-9;
        assert!(
            site.slope_deg <= tolerance,
            "no spin: {} deg at {:?}",
            site.slope_deg,
            site.centroid_m
        );
        assert_eq!(site.effective_m_s2, site.gravity_m_s2);
    }
}

/// `-w x (w x r)` is `w^2` times the distance from the axis, pointing away from it; the
/// latitude and longitude of a facet are its centroid's; `facets` on all threads returns
/// what `facet_gravity` does for each facet, bit for bit.
#[test]
fn centrifugal_latitude_longitude_and_all_facets() {
    let w: f64 = 1e-3;
    let r = [3.0, -4.0, 12.0];
    assert_eq!(centrifugal(Z, w, r), [w * w * 3.0, -w * w * 4.0, 0.0]);
    let x = unit_axis([2.0, 0.0, 0.0]).unwrap();
    assert_eq!(x, [1.0, 0.0, 0.0]);
    assert_eq!(centrifugal(x, w, r), [0.0, -w * w * 4.0, w * w * 12.0]);
    let tilted = unit_axis([1.0, 1.0, 0.0]).unwrap();
    let c = centrifugal(tilted, w, [1.0, -1.0, 5.0]);
    let expected = [w * w, -w * w, 5.0 * w * w];
    assert!(norm(sub(c, expected)) <= 1e-14 * w * w, "{c:?}");
    assert!(
        unit_axis([0.0; 3])
            .unwrap_err()
            .to_string()
            .contains("spin axis")
    );
    assert!(unit_axis([f64::NAN, 0.0, 1.0]).is_err());

    let poly = Polyhedron::new(checked(icosphere(50.0, 2)), RHO).unwrap();
    let spin = unit_axis([0.1, 0.2, 1.0]).unwrap();
    let every = facets(&poly, spin, 2e-4);
    assert_eq!(every.len(), 320);
    for (f, site) in every.iter().enumerate() {
        assert_eq!(*site, facet_gravity(&poly, f, spin, 2e-4));
        // About the spin axis a: the latitude from its equator, the longitude east from the
        // mesh's x made perpendicular to a.
        let c = site.centroid_m;
        let lat = (dot(c, spin) / norm(c)).asin().to_degrees();
        let e1 = unit(sub([1.0, 0.0, 0.0], scale(spin, spin[0])));
        let e2 = cross(spin, e1);
        let lon = dot(c, e2).atan2(dot(c, e1)).to_degrees();
        assert!((site.latitude_deg - lat).abs() < 1e-9 && (site.longitude_deg - lon).abs() < 1e-9);
        assert!((-90.0..=90.0).contains(&site.latitude_deg));
        assert!(site.longitude_deg > -180.0 && site.longitude_deg <= 180.0);
    }
}

/// The spin frame is right-handed and orthonormal with the axis third; about `+z` the
/// latitude and longitude are the mesh frame's own, to the bit; an axis near `x` takes its
/// first axis from `y`.
#[test]
fn the_spin_frame_and_its_latitudes() {
    for axis in [
        Z,
        unit_axis([1.0, 2.0, 3.0]).unwrap(),
        unit_axis([1.0, 0.01, 0.0]).unwrap(),
        unit_axis([0.0, 0.0, -1.0]).unwrap(),
    ] {
        let [e1, e2, a] = spin_frame(axis);
        assert_eq!(a, axis);
        for (u, v, want) in [
            (e1, e1, 1.0),
            (e2, e2, 1.0),
            (e1, e2, 0.0),
            (e1, a, 0.0),
            (e2, a, 0.0),
        ] {
            assert!((dot(u, v) - want).abs() < 1e-15, "{axis:?}");
        }
        assert!(
            norm(sub(cross(e1, e2), a)) < 1e-15,
            "{axis:?}: not right-handed"
        );
        // The axis is latitude 90, e1 is longitude 0, e2 longitude 90.
        assert!((latitude_longitude(axis, scale(a, 7.0)).0 - 90.0).abs() < 1e-12);
        let (lat, lon) = latitude_longitude(axis, scale(e1, 3.0));
        assert!(
            lat.abs() < 1e-12 && lon.abs() < 1e-12,
            "{axis:?}: {lat} {lon}"
        );
        assert!((latitude_longitude(axis, e2).1 - 90.0).abs() < 1e-12);
    }
    // Near x the first axis comes from y, so it is still well defined.
    assert!(spin_frame(unit_axis([1.0, 0.01, 0.0]).unwrap())[0][1] > 0.99);
    for r in [[3.0, -4.0, 12.0], [-1.0, 0.0, -2.0], [0.5, 2.5, 0.0]] {
        let (lat, lon) = latitude_longitude(Z, r);
        assert_eq!(lat, r[2].atan2(r[0].hypot(r[1])).to_degrees());
        assert_eq!(lon, r[1].atan2(r[0]).to_degrees());
    }
}

/// Not a test of time (none asserts one): prints the wall time of `facets` on a
/// 12,000-facet sphere, run by hand with `--ignored --nocapture`.
#[test]
#[ignore]
fn facets_wall_time_on_12000_facets() {
    let mesh = checked(uv_sphere(1000.0, 61, 100));
    assert_eq!(mesh.facet_geometry().len(), 12_000);
    let poly = Polyhedron::new(mesh, RHO).unwrap();
    let start = std::time::Instant::now();
    let all = facets(&poly, Z, 3e-4);
    eprintln!(
        "facets on {} facets and {} edges: {:.2} s on {} threads",
        all.len(),
        poly.mesh().edges().len(),
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
}
