//! A triangle mesh, and its check: a closed, manifold, consistently and outward-oriented
//! surface of non-degenerate triangles, with the geometry the gravity needs (per facet its
//! centroid, outward normal and area; the body's volume, centre of mass and surface area).
//!
//! Facets that intersect each other are refused (intersect.rs: a bounding-volume hierarchy
//! of the facets' boxes, exact tests of the pairs whose boxes overlap). Not checked: a
//! surface that pinches at a vertex without passing through itself (two cones touching at
//! their tips, sharing the vertex). An unused vertex is allowed.

use super::error::ShapeError;
use super::intersect::{Intersection, first_intersection};
use super::vec3::{add, cross, dot, norm, scale, sub};

/// A triangle mesh in metres, in the shape model's body-fixed frame. A facet lists its three
/// vertices (0-based indices into `vertices`) counter-clockwise seen from outside the body.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// The vertices, m.
    pub vertices: Vec<[f64; 3]>,
    /// The triangles, each three indices into `vertices`, counter-clockwise from outside.
    pub facets: Vec<[u32; 3]>,
}

/// A facet's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetGeometry {
    /// The centroid (mean of the three vertices), m.
    pub centroid_m: [f64; 3],
    /// The unit outward normal.
    pub normal: [f64; 3],
    /// The area, m^2.
    pub area_m2: f64,
}

/// An edge of a checked mesh: the two facets that share it, the first running along it
/// from `vertices[0]` to `vertices[1]`, the second the other way.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// The edge's vertices (0-based), in the direction `facets[0]` runs along it.
    pub vertices: [u32; 2],
    /// The two facets (0-based) that share the edge.
    pub facets: [u32; 2],
}

/// A mesh that passed [`Mesh::check`], with its edges and geometry.
#[derive(Debug, Clone)]
pub struct CheckedMesh {
    mesh: Mesh,
    edges: Vec<Edge>,
    geometry: Vec<FacetGeometry>,
    volume_m3: f64,
    centre_of_mass_m: [f64; 3],
    surface_area_m2: f64,
    size_m: f64,
}

impl CheckedMesh {
    /// The mesh.
    #[must_use]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }
    /// Every edge once, in the order of its first use in the facets.
    #[must_use]
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }
    /// Each facet's centroid, outward normal and area, in facet order.
    #[must_use]
    pub fn facet_geometry(&self) -> &[FacetGeometry] {
        &self.geometry
    }
    /// The enclosed volume, m^3 (positive).
    #[must_use]
    pub fn volume_m3(&self) -> f64 {
        self.volume_m3
    }
    /// The centre of mass of the enclosed volume at constant density, m, in the mesh's
    /// frame. A shape model is normally given about its centre of mass: this is then near
    /// the origin (nothing is recentred here).
    #[must_use]
    pub fn centre_of_mass_m(&self) -> [f64; 3] {
        self.centre_of_mass_m
    }
    /// The surface area, m^2.
    #[must_use]
    pub fn surface_area_m2(&self) -> f64 {
        self.surface_area_m2
    }
    /// The diagonal of the bounding box of the vertices the facets use, m.
    #[must_use]
    pub fn size_m(&self) -> f64 {
        self.size_m
    }
}

/// The most vertices a shape model may have (a 3-million-facet model has about 1.5 million).
pub const MAX_VERTICES: usize = 5_000_000;

/// The most triangles a shape model may have, after splitting polygons.
pub const MAX_FACETS: usize = 5_000_000;

/// The largest coordinate of a vertex, m: its cube, 1e300, leaves room below the largest
/// number (1.8e308) for the sums of products of three coordinates the volume takes.
pub const MAX_COORDINATE_M: f64 = 1e100;

/// A facet's area below this fraction of the squared size of the mesh is degenerate.
pub const DEGENERATE_AREA: f64 = 1e-12;

fn refuse<T>(message: String) -> Result<T, ShapeError> {
    Err(ShapeError::Mesh(message))
}

impl Mesh {
    /// Checks that the mesh is a closed, manifold, consistently oriented surface of
    /// non-degenerate triangles whose facets face outwards, and computes its geometry.
    /// Refused, naming the first problem in file order (vertices and facets numbered from 1
    /// as in the file): fewer than 4 facets, a facet naming a vertex that does not exist or a
    /// coordinate that is not finite or beyond [`MAX_COORDINATE_M`] (an overflow), a facet repeating a vertex or of area below
    /// [`DEGENERATE_AREA`] times the squared bounding-box diagonal, an edge used by one
    /// facet (not closed), by more than two (not manifold), or twice in the same direction
    /// (not consistently oriented), a surface that encloses a negative volume (inverted:
    /// its facets face inwards) or none, and two facets that intersect other than at the
    /// vertex or edge they share (the first pair in file order; a mesh whose facets' boxes
    /// overlap in too many pairs to check is refused too).
    pub fn check(self) -> Result<CheckedMesh, ShapeError> {
        let n = self.facets.len();
        if n < 4 {
            return refuse(format!("{n} facets: a closed surface needs at least 4"));
        }
        if n > MAX_FACETS {
            return refuse(format!("{n} facets: at most {MAX_FACETS} are read"));
        }
        let size_m = self.used_size()?;
        let geometry = self.geometry(size_m)?;
        let edges = self.edges()?;
        let (volume_m3, centre_of_mass_m) = self.volume(size_m)?;
        self.intersections()?;
        let surface_area_m2 = geometry.iter().map(|g| g.area_m2).sum();
        Ok(CheckedMesh {
            mesh: self,
            edges,
            geometry,
            volume_m3,
            centre_of_mass_m,
            surface_area_m2,
            size_m,
        })
    }

    /// The vertices of facet `f`, after [`Mesh::used_size`] checked the indices.
    fn corners(&self, f: usize) -> [[f64; 3]; 3] {
        self.facets[f].map(|v| self.vertices[v as usize])
    }

    /// The bounding-box diagonal of the vertices the facets use; refuses an index out of
    /// range and a coordinate that is not finite.
    fn used_size(&self) -> Result<f64, ShapeError> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        // The vertex farthest out along an axis, with the first facet that names it.
        let mut farthest = (0.0_f64, 0, 0);
        for (f, facet) in self.facets.iter().enumerate() {
            for &v in facet {
                let Some(p) = self.vertices.get(v as usize) else {
                    return refuse(format!(
                        "facet {} names vertex {}, but the mesh has {} vertices",
                        f + 1,
                        v as u64 + 1,
                        self.vertices.len()
                    ));
                };
                if !p.iter().all(|x| x.is_finite()) {
                    return refuse(format!("vertex {} is not finite: {p:?}", v as u64 + 1));
                }
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
                let out = p.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                if out > farthest.0 {
                    farthest = (out, v, f);
                }
            }
        }
        // The volume and the gravity take products of three coordinates: beyond
        // MAX_COORDINATE_M they overflow, and every check after this would blame a facet for
        // what is a coordinate out of range.
        let (out, v, f) = farthest;
        if out > MAX_COORDINATE_M {
            let p = self.vertices[v as usize];
            return refuse(format!(
                "vertex {} (of facet {}) at {p:?} m overflows: the volume and the gravity \
                 take products of three coordinates, numbers only for coordinates of at most \
                 {MAX_COORDINATE_M:e} m (check the coordinates and the units)",
                v as u64 + 1,
                f + 1,
            ));
        }
        let size_m = norm(sub(hi, lo));
        Ok(size_m)
    }

    /// Each facet's centroid, normal and area; refuses a degenerate facet.
    fn geometry(&self, size_m: f64) -> Result<Vec<FacetGeometry>, ShapeError> {
        let mut out = Vec::with_capacity(self.facets.len());
        for (f, &[a, b, c]) in self.facets.iter().enumerate() {
            let named = || {
                format!(
                    "degenerate facet {} (vertices {} {} {})",
                    f + 1,
                    a + 1,
                    b + 1,
                    c + 1
                )
            };
            if a == b || b == c || c == a {
                let v = if a == b || a == c { a } else { b };
                return refuse(format!("{}: vertex {} repeats", named(), v + 1));
            }
            let [pa, pb, pc] = self.corners(f);
            let twice = cross(sub(pb, pa), sub(pc, pa));
            let area_m2 = 0.5 * norm(twice);
            if !(area_m2 >= DEGENERATE_AREA * size_m * size_m && area_m2 > 0.0) {
                return refuse(format!(
                    "{}: its area {area_m2:.3e} m^2 is below {DEGENERATE_AREA:e} of the squared \
                     size of the mesh ({size_m:.6e} m across)",
                    named()
                ));
            }
            out.push(FacetGeometry {
                centroid_m: scale(add(add(pa, pb), pc), 1.0 / 3.0),
                normal: scale(twice, 0.5 / area_m2),
                area_m2,
            });
        }
        Ok(out)
    }

    /// Every edge once with its two facets; refuses an edge used by one facet, by more than
    /// two, or twice in the same direction, the first such edge in file order.
    fn edges(&self) -> Result<Vec<Edge>, ShapeError> {
        // (low vertex, high vertex, position of the use in file order = 3 facet + corner).
        let mut uses: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * self.facets.len());
        for (f, facet) in self.facets.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (facet[k], facet[(k + 1) % 3]);
                uses.push((a.min(b), a.max(b), (3 * f + k) as u32));
            }
        }
        uses.sort_unstable();
        let mut edges = Vec::with_capacity(uses.len() / 2);
        let mut worst: Option<(u32, String)> = None;
        for group in uses.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let first = group[0].2;
            if let Some(problem) = self.edge_problem(group) {
                if worst.as_ref().is_none_or(|(at, _)| first < *at) {
                    worst = Some((first, problem));
                }
            } else {
                let [a, b] = self.directed(first);
                edges.push((
                    first,
                    Edge {
                        vertices: [a, b],
                        facets: [first / 3, group[1].2 / 3],
                    },
                ));
            }
        }
        if let Some((_, problem)) = worst {
            return refuse(problem);
        }
        edges.sort_unstable_by_key(|e| e.0);
        Ok(edges.into_iter().map(|e| e.1).collect())
    }

    /// The use `3 f + k` of an edge: its vertices in the direction facet `f` runs along it.
    fn directed(&self, at: u32) -> [u32; 2] {
        let facet = self.facets[at as usize / 3];
        let k = at as usize % 3;
        [facet[k], facet[(k + 1) % 3]]
    }

    /// What is wrong with an edge used as `group` lists (sorted in file order), if anything.
    fn edge_problem(&self, group: &[(u32, u32, u32)]) -> Option<String> {
        let [a, b] = self.directed(group[0].2);
        let (a, b) = (a + 1, b + 1);
        let facet = |i: usize| group[i].2 / 3 + 1;
        match group.len() {
            1 => Some(format!(
                "not closed: edge {a}-{b} (vertices numbered as in the file) belongs to facet \
                 {} only",
                facet(0)
            )),
            2 if self.directed(group[1].2) == self.directed(group[0].2) => Some(format!(
                "not consistently oriented: facets {} and {} both run along edge {a}-{b} from \
                 vertex {a} to vertex {b} (one of them winds the other way)",
                facet(0),
                facet(1)
            )),
            2 => None,
            k => {
                let list: Vec<String> = (0..k.min(6)).map(|i| facet(i).to_string()).collect();
                Some(format!(
                    "not manifold: edge {a}-{b} is shared by {k} facets ({}{})",
                    list.join(", "),
                    if k > 6 { ", ..." } else { "" }
                ))
            }
        }
    }

    /// Refuses facets that intersect each other, naming the first pair in file order.
    fn intersections(&self) -> Result<(), ShapeError> {
        match first_intersection(&self.vertices, &self.facets) {
            Ok(()) => Ok(()),
            Err(Intersection::Facets(f, g)) => {
                let named = |f: usize| {
                    let [a, b, c] = self.facets[f].map(|v| v + 1);
                    format!("{} (vertices {a} {b} {c})", f + 1)
                };
                refuse(format!(
                    "it intersects itself: facets {} and {} cross each other (two bodies \
                     overlapping in one file, or a surface folded through itself)",
                    named(f),
                    named(g)
                ))
            }
            Err(Intersection::TooManyPairs(pairs, allowed)) => refuse(format!(
                "its facets' bounding boxes overlap in more than {allowed} pairs ({pairs} \
                 counted, {} facets): too many to check whether facets intersect each other \
                 (long thin facets fanned about one place?)",
                self.facets.len()
            )),
        }
    }

    /// The enclosed volume and its centre of mass; refuses an inverted surface (negative
    /// signed volume) and one that encloses none.
    fn volume(&self, size_m: f64) -> Result<(f64, [f64; 3]), ShapeError> {
        // Tetrahedra from the mesh's middle, so that far-off coordinates cost no digits.
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for facet in &self.facets {
            for &v in facet {
                let p = self.vertices[v as usize];
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let middle = scale(add(lo, hi), 0.5);
        let mut six_volume = 0.0;
        let mut moment = [0.0; 3];
        for f in 0..self.facets.len() {
            let [a, b, c] = self.corners(f).map(|p| sub(p, middle));
            let v6 = dot(a, cross(b, c));
            six_volume += v6;
            moment = add(moment, scale(add(add(a, b), c), v6));
        }
        let volume = six_volume / 6.0;
        if volume.abs() <= 1e-12 * size_m.powi(3) {
            return refuse(format!(
                "the surface encloses no volume ({volume:.3e} m^3 for a mesh {size_m:.6e} m \
                 across)"
            ));
        }
        if volume < 0.0 {
            return refuse(format!(
                "inverted: its facets face inwards (they wind clockwise seen from outside; the \
                 volume they enclose counts {volume:.6e} m^3)"
            ));
        }
        Ok((volume, add(middle, scale(moment, 1.0 / (4.0 * six_volume)))))
    }
}
