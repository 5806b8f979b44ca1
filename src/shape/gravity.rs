//! The gravity of a constant-density polyhedron, in closed form (Werner and Scheeres 1997,
//! "Exterior gravitation of a polyhedron derived and compared with harmonic and mascon
//! gravitation representations of asteroid 4769 Castalia", Celest. Mech. Dyn. Astron. 65,
//! 313-344; docs/MODEL.md, "The shape model and its gravity").
//!
//! With `r_e` from the field point to a vertex of edge `e`, `r_f` to a vertex of facet `f`,
//! the edge dyad `E_e = n_A n_e^A^T + n_B n_e^B^T` (the two facets' outward normals and
//! their outward normals to the edge in their planes) and the facet dyad `F_f = n_f n_f^T`:
//!
//! ```text
//! U      = (G rho / 2) (sum_e r_e . E_e r_e L_e  -  sum_f r_f . F_f r_f w_f)
//! grad U = -G rho sum_e E_e r_e L_e  +  G rho sum_f F_f r_f w_f
//! lap U  = -G rho sum_f w_f        (-4 pi G rho inside, 0 outside)
//! ```
//!
//! `L_e = ln((r_i + r_j + e) / (r_i + r_j - e))` for the edge's length `e` and the distances
//! `r_i`, `r_j` to its ends, and `w_f` is the signed solid angle of the facet. The
//! acceleration is `grad U`; [`Field::potential_m2_s2`] is `-U`, the potential energy of a
//! unit mass (`-G M / r` far away).

use super::error::ShapeError;
use super::mesh::CheckedMesh;
use super::vec3::{add, cross, dot, norm, scale, sub};

/// The constant of gravitation, m^3 kg^-1 s^-2 (CODATA 2018).
pub const G: f64 = 6.67430e-11;

/// The gravity at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// The potential energy of a unit mass, m^2/s^2 (negative, `-G M / r` far away).
    pub potential_m2_s2: f64,
    /// The attraction, m/s^2.
    pub acceleration_m_s2: [f64; 3],
    /// The Laplacian of the potential `U = -potential`, 1/s^2: `-4 pi G rho` inside the body,
    /// 0 outside (the sum of the facets' solid angles: a check of where the point is).
    pub laplacian_s2: f64,
}

/// An edge's share of the gravity: its ends, its length and its dyad `E_e`.
#[derive(Debug, Clone, Copy)]
struct EdgeTerm {
    ends: [u32; 2],
    length_m: f64,
    dyad: [[f64; 3]; 3],
}

/// A facet's share: its vertices, unit normal (the dyad `F_f = n n^T`, applied in this
/// rank-one form) and twice its area.
#[derive(Debug, Clone, Copy)]
struct FacetTerm {
    corners: [u32; 3],
    normal: [f64; 3],
    twice_area_m2: f64,
}

/// A constant-density polyhedron with its edge and facet dyads precomputed: the gravity at
/// a point costs one pass over the edges and one over the facets, without allocating.
/// Everything is in the mesh's own frame (see [`CheckedMesh::centre_of_mass_m`]).
#[derive(Debug, Clone)]
pub struct Polyhedron {
    mesh: CheckedMesh,
    density_kg_m3: f64,
    edges: Vec<EdgeTerm>,
    facets: Vec<FacetTerm>,
}

impl Polyhedron {
    /// The polyhedron of a checked mesh at a density in kg/m^3 (positive and finite).
    pub fn new(mesh: CheckedMesh, density_kg_m3: f64) -> Result<Self, ShapeError> {
        if !(density_kg_m3.is_finite() && density_kg_m3 > 0.0) {
            return Err(ShapeError::Value(format!(
                "the density must be a positive number of kg/m^3, not {density_kg_m3}"
            )));
        }
        let vertices = &mesh.mesh().vertices;
        let geometry = mesh.facet_geometry();
        let edges = mesh
            .edges()
            .iter()
            .map(|e| {
                let [i, j] = e.vertices;
                let along = sub(vertices[j as usize], vertices[i as usize]);
                let length_m = norm(along);
                let d = scale(along, 1.0 / length_m);
                // Facet A runs i -> j, facet B j -> i: each one's outward edge normal is its
                // direction along the edge crossed with its own normal.
                let n_a = geometry[e.facets[0] as usize].normal;
                let n_b = geometry[e.facets[1] as usize].normal;
                let e_a = cross(d, n_a);
                let e_b = cross(scale(d, -1.0), n_b);
                let dyad = std::array::from_fn(|r| {
                    std::array::from_fn(|c| n_a[r] * e_a[c] + n_b[r] * e_b[c])
                });
                EdgeTerm {
                    ends: [i, j],
                    length_m,
                    dyad,
                }
            })
            .collect();
        let facets = mesh
            .mesh()
            .facets
            .iter()
            .zip(geometry)
            .map(|(&corners, g)| FacetTerm {
                corners,
                normal: g.normal,
                twice_area_m2: 2.0 * g.area_m2,
            })
            .collect();
        Ok(Polyhedron {
            mesh,
            density_kg_m3,
            edges,
            facets,
        })
    }

    /// The checked mesh.
    #[must_use]
    pub fn mesh(&self) -> &CheckedMesh {
        &self.mesh
    }

    /// The density, kg/m^3.
    #[must_use]
    pub fn density_kg_m3(&self) -> f64 {
        self.density_kg_m3
    }

    /// The mass, kg.
    #[must_use]
    pub fn mass_kg(&self) -> f64 {
        self.density_kg_m3 * self.mesh.volume_m3()
    }

    /// The centre of mass, m, in the mesh's frame (a shape model is normally given about
    /// it; nothing is recentred).
    #[must_use]
    pub fn centre_of_mass_m(&self) -> [f64; 3] {
        self.mesh.centre_of_mass_m()
    }

    /// The gravity at `r` (m, mesh frame). Not defined on an edge or a vertex; on a facet
    /// use [`Polyhedron::field_on_facet`].
    #[must_use]
    pub fn field(&self, r: [f64; 3]) -> Field {
        self.sum(r, usize::MAX)
    }

    /// The attraction at `r`, m/s^2 (see [`Polyhedron::field`]).
    #[must_use]
    pub fn acceleration(&self, r: [f64; 3]) -> [f64; 3] {
        self.field(r).acceleration_m_s2
    }

    /// The potential energy of a unit mass at `r`, m^2/s^2 (see [`Polyhedron::field`]).
    #[must_use]
    pub fn potential(&self, r: [f64; 3]) -> f64 {
        self.field(r).potential_m2_s2
    }

    /// The Laplacian of `U` at `r`, 1/s^2: `-4 pi G rho` inside, 0 outside.
    #[must_use]
    pub fn laplacian(&self, r: [f64; 3]) -> f64 {
        self.field(r).laplacian_s2
    }

    /// The gravity at the centroid of `facet` (0-based), on the surface. The facet's own
    /// solid angle is undefined there (`+2 pi` from inside, `-2 pi` from outside), but it
    /// enters the potential and the attraction multiplied by `n_f . r_f`, which is zero for
    /// a point in the facet's plane: its term is left out, and the potential and the
    /// attraction are the limits from either side (both are continuous across a facet). The
    /// centroid is off every edge, so every `L_e` is finite. The Laplacian is the limit
    /// from outside, where a lander stands (about 0; `w_f = -2 pi`). Panics if `facet` is
    /// not a facet of the mesh (a caller's mistake, never the file's).
    #[must_use]
    pub fn field_on_facet(&self, facet: usize) -> Field {
        let centroid = self.mesh.facet_geometry()[facet].centroid_m;
        let mut field = self.sum(centroid, facet);
        field.laplacian_s2 += self.density_kg_m3 * G * 2.0 * std::f64::consts::PI;
        field
    }

    /// The sums of Werner and Scheeres at `r`, without facet `skip` (usize::MAX: none).
    fn sum(&self, r: [f64; 3], skip: usize) -> Field {
        let vertices = &self.mesh.mesh().vertices;
        let mut edge_potential = 0.0;
        let mut edge_pull = [0.0; 3];
        for e in &self.edges {
            let ri = sub(vertices[e.ends[0] as usize], r);
            let rj = sub(vertices[e.ends[1] as usize], r);
            let ends = norm(ri) + norm(rj);
            // ln((s + e) / (s - e)) as ln_1p(2e / (s - e)): exact digits far away, where
            // the ratio is near 1.
            let l_e = (2.0 * e.length_m / (ends - e.length_m)).ln_1p();
            let er = [dot(e.dyad[0], ri), dot(e.dyad[1], ri), dot(e.dyad[2], ri)];
            edge_potential += dot(ri, er) * l_e;
            edge_pull = add(edge_pull, scale(er, l_e));
        }
        let mut facet_potential = 0.0;
        let mut facet_pull = [0.0; 3];
        let mut solid_angle = 0.0;
        for (f, t) in self.facets.iter().enumerate() {
            if f == skip {
                continue;
            }
            let [a, b, c] = t.corners.map(|v| sub(vertices[v as usize], r));
            let height = dot(t.normal, a);
            let (la, lb, lc) = (norm(a), norm(b), norm(c));
            // a . (b x c) = a . ((b - a) x (c - a)) = 2 area (n . a): exact far away, where
            // the three vectors are nearly parallel.
            let triple = t.twice_area_m2 * height;
            let below = la * lb * lc + la * dot(b, c) + lb * dot(c, a) + lc * dot(a, b);
            let w_f = 2.0 * triple.atan2(below);
            solid_angle += w_f;
            facet_potential += height * height * w_f;
            facet_pull = add(facet_pull, scale(t.normal, height * w_f));
        }
        let g_rho = G * self.density_kg_m3;
        Field {
            potential_m2_s2: -0.5 * g_rho * (edge_potential - facet_potential),
            acceleration_m_s2: std::array::from_fn(|k| g_rho * (facet_pull[k] - edge_pull[k])),
            laplacian_s2: -g_rho * solid_angle,
        }
    }
}
