//! Each facet's effective gravity and slope: the polyhedron's attraction at its centroid,
//! plus the centrifugal acceleration of the body's spin, against its outward normal.

use super::error::ShapeError;
use super::gravity::{G, Polyhedron};
use super::tree::{FacetTree, OPENING};
use super::vec3::{add, cross, dot, norm, scale};
use rayon::prelude::*;

/// A facet's gravity and slope.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetGravity {
    /// The centroid, m (mesh frame).
    pub centroid_m: [f64; 3],
    /// The unit outward normal.
    pub normal: [f64; 3],
    /// The area, m^2.
    pub area_m2: f64,
    /// The polyhedron's attraction at the centroid, m/s^2.
    pub gravity_m_s2: [f64; 3],
    /// The attraction plus the centrifugal acceleration of the spin, m/s^2.
    pub effective_m_s2: [f64; 3],
    /// The magnitude of `effective_m_s2`, m/s^2.
    pub effective_magnitude_m_s2: f64,
    /// The slope, deg: the angle between the outward normal and minus the effective gravity,
    /// in [0, 180]. Above 90 the effective gravity points away from the surface (an overhang,
    /// or a spin that throws things off there); NaN where the effective gravity is zero.
    pub slope_deg: f64,
    /// The centroid's latitude, deg: spherical, from the spin's equatorial plane (the spin
    /// axis at +90; [`latitude_longitude`]), in [-90, 90].
    pub latitude_deg: f64,
    /// The centroid's longitude, deg, east (counter-clockwise about the spin axis) from the
    /// spin frame's first axis ([`spin_frame`]), in (-180, 180].
    pub longitude_deg: f64,
}

/// The centrifugal acceleration `-w x (w x r)` at `r` (m, mesh frame), `w = omega axis`,
/// of a spin about the axis `spin_axis_unit` (a unit vector) through the mesh frame's origin
/// (a shape model's centre of mass, in its convention), m/s^2.
#[must_use]
pub fn centrifugal(spin_axis_unit: [f64; 3], omega_rad_s: f64, r: [f64; 3]) -> [f64; 3] {
    let w = scale(spin_axis_unit, omega_rad_s);
    scale(cross(w, cross(w, r)), -1.0)
}

/// `axis` scaled to unit length; refused if it is zero or not finite.
pub fn unit_axis(axis: [f64; 3]) -> Result<[f64; 3], ShapeError> {
    let length = norm(axis);
    if !(length.is_finite() && length > 0.0) {
        return Err(ShapeError::Value(format!(
            "the spin axis must be a finite, non-zero vector, not {axis:?}"
        )));
    }
    Ok(scale(axis, 1.0 / length))
}

/// The frame latitudes and longitudes are taken in, for a spin about `spin_axis_unit` (a
/// unit vector): `[e1, e2, a]`, right-handed, `a` the axis, `e1` the mesh frame's `x` made
/// perpendicular to it (its `y` where `x` lies within about 6 deg of the axis), `e2 = a x
/// e1`. For the axis `+z` it is the mesh frame itself.
#[must_use]
pub fn spin_frame(spin_axis_unit: [f64; 3]) -> [[f64; 3]; 3] {
    let a = spin_axis_unit;
    let across = |v: [f64; 3]| add(v, scale(a, -dot(v, a)));
    let mut e1 = across([1.0, 0.0, 0.0]);
    if norm(e1) < 0.1 {
        e1 = across([0.0, 1.0, 0.0]);
    }
    let e1 = scale(e1, 1.0 / norm(e1));
    [e1, cross(a, e1), a]
}

/// The latitude and longitude, deg, of the point `r` (m, mesh frame) about the spin axis
/// `spin_axis_unit`: spherical in [`spin_frame`], the latitude from the spin's equatorial
/// plane, the longitude east from `e1`. For the axis `+z` exactly, the mesh frame's own
/// `atan2(z, hypot(x, y))` and `atan2(y, x)`, to the bit.
#[must_use]
pub fn latitude_longitude(spin_axis_unit: [f64; 3], r: [f64; 3]) -> (f64, f64) {
    let [x, y, z] = if spin_axis_unit == [0.0, 0.0, 1.0] {
        r
    } else {
        spin_frame(spin_axis_unit).map(|e| dot(r, e))
    };
    (z.atan2(x.hypot(y)).to_degrees(), y.atan2(x).to_degrees())
}

/// The slope, deg, of a surface with unit outward normal `normal` under the effective
/// gravity `effective`: `acos(-n . g / |g|)`, in [0, 180] (NaN if `effective` is zero).
#[must_use]
pub fn slope_deg(normal: [f64; 3], effective: [f64; 3]) -> f64 {
    let cos = (-dot(normal, effective) / norm(effective)).clamp(-1.0, 1.0);
    cos.acos().to_degrees()
}

/// How the facets' attraction is summed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GravitySum {
    /// Every facet and edge at every facet, in closed form ([`Polyhedron::field_on_facet`]):
    /// about `2.5 F^2` terms for `F` facets.
    Exact,
    /// The facets near a point in closed form, groups of facets far from it by their
    /// moments ([`FacetTree`]), opened at this angle: about `F log F` terms.
    Tree {
        /// The opening angle, in `[0, 1)` ([`crate::shape::OPENING`] by default; 0 sums
        /// every facet exactly, facet by facet).
        opening: f64,
    },
}

/// The most facets [`GravitySum::auto`] sums exactly: the exact sum of so many takes about
/// 6 s on 2 cores (9.3 s at 20,480, measured), and the landing-site maps of the README
/// (1,996 and 12,192 facets) stay as they were.
pub const EXACT_UP_TO: usize = 16_384;

impl GravitySum {
    /// The exact sum for a model of at most [`EXACT_UP_TO`] facets, the tree at
    /// [`OPENING`] above.
    #[must_use]
    pub fn auto(facets: usize) -> Self {
        if facets <= EXACT_UP_TO {
            GravitySum::Exact
        } else {
            GravitySum::Tree { opening: OPENING }
        }
    }
}

/// Facet `facet`'s (0-based) gravity and slope on `poly` spinning at `omega_rad_s` about
/// `spin_axis_unit` (see [`centrifugal`]); the attraction as [`Polyhedron::field_on_facet`]
/// takes it. Panics if `facet` is not a facet of the mesh (a caller's mistake, never the
/// file's).
#[must_use]
pub fn facet_gravity(
    poly: &Polyhedron,
    facet: usize,
    spin_axis_unit: [f64; 3],
    omega_rad_s: f64,
) -> FacetGravity {
    let gravity = poly.field_on_facet(facet).acceleration_m_s2;
    with_spin(poly, facet, gravity, spin_axis_unit, omega_rad_s)
}

/// Facet `facet`'s numbers, given its attraction `gravity` (m/s^2).
fn with_spin(
    poly: &Polyhedron,
    facet: usize,
    gravity: [f64; 3],
    spin_axis_unit: [f64; 3],
    omega_rad_s: f64,
) -> FacetGravity {
    let g = poly.mesh().facet_geometry()[facet];
    let c = g.centroid_m;
    let effective = add(gravity, centrifugal(spin_axis_unit, omega_rad_s, c));
    let (latitude_deg, longitude_deg) = latitude_longitude(spin_axis_unit, c);
    FacetGravity {
        centroid_m: c,
        normal: g.normal,
        area_m2: g.area_m2,
        gravity_m_s2: gravity,
        effective_m_s2: effective,
        effective_magnitude_m_s2: norm(effective),
        slope_deg: slope_deg(g.normal, effective),
        latitude_deg,
        longitude_deg,
    }
}

/// Every facet's gravity and slope, in facet order ([`facet_gravity`]), on all of rayon's
/// threads, summed exactly: each facet costs one pass over the edges and facets, so a
/// model of `F` facets costs about `2.5 F^2` terms. The result does not depend on the
/// number of threads.
#[must_use]
pub fn facets(poly: &Polyhedron, spin_axis_unit: [f64; 3], omega_rad_s: f64) -> Vec<FacetGravity> {
    facets_told(poly, spin_axis_unit, omega_rad_s, GravitySum::Exact, |_| {})
}

/// Every facet's gravity and slope, in facet order, summed as `sum` says, on all of rayon's
/// threads, calling `done(k)` as `k` more facets are done (from any thread: a progress
/// bar). The result does not depend on the number of threads. The tree's attraction is
/// `-G rho` times [`FacetTree::sums`].
#[must_use]
pub fn facets_told(
    poly: &Polyhedron,
    spin_axis_unit: [f64; 3],
    omega_rad_s: f64,
    sum: GravitySum,
    done: impl Fn(usize) + Sync,
) -> Vec<FacetGravity> {
    let count = poly.mesh().facet_geometry().len();
    let gravity: Vec<[f64; 3]> = match sum {
        GravitySum::Exact => (0..count)
            .into_par_iter()
            .map(|f| {
                let g = poly.field_on_facet(f).acceleration_m_s2;
                done(1);
                g
            })
            .collect(),
        GravitySum::Tree { opening } => {
            let tree = FacetTree::new(poly.mesh(), opening);
            return tree_facets(poly, &tree, spin_axis_unit, omega_rad_s, done);
        }
    };
    spun(poly, gravity, spin_axis_unit, omega_rad_s)
}

/// [`facets_told`] by the tree `tree` of `poly`'s mesh, built before (for an estimate of
/// the time from a few of its leaves, [`FacetTree::leaf_sums`]).
///
/// # Panics
/// If `tree` was built from another mesh with fewer facets (a caller's mistake).
#[must_use]
pub fn tree_facets(
    poly: &Polyhedron,
    tree: &FacetTree,
    spin_axis_unit: [f64; 3],
    omega_rad_s: f64,
    done: impl Fn(usize) + Sync,
) -> Vec<FacetGravity> {
    let g_rho = G * poly.density_kg_m3();
    let gravity = tree
        .sums(done)
        .into_iter()
        .map(|s| scale(s, -g_rho))
        .collect();
    spun(poly, gravity, spin_axis_unit, omega_rad_s)
}

/// Every facet's numbers from its attraction.
fn spun(
    poly: &Polyhedron,
    gravity: Vec<[f64; 3]>,
    spin_axis_unit: [f64; 3],
    omega_rad_s: f64,
) -> Vec<FacetGravity> {
    gravity
        .into_par_iter()
        .enumerate()
        .map(|(f, g)| with_spin(poly, f, g, spin_axis_unit, omega_rad_s))
        .collect()
}
