//! The shape model of a small body and its gravity: a Wavefront OBJ file (obj.rs), a
//! vertex-facet plate file (plate.rs: PDS `.tab`, SBMT `.plt`) or Gaskell's ICQ file
//! (icq.rs: SPC's `SHAPE.TXT`) read into a mesh, the format chosen by the file's content
//! (read.rs), the mesh checked to be a closed, consistently oriented, outward-facing surface
//! with its geometry (mesh.rs) and no facets that intersect each other (intersect.rs), the
//! constant-density polyhedron's gravity in closed form (gravity.rs: Werner and Scheeres
//! 1997), at every facet also by a tree of the facets in about `F log F` (tree.rs), and per
//! facet the spin's centrifugal acceleration, the effective gravity and the slope
//! (facets.rs), and each facet's roughness against its neighbours (roughness.rs).
//! docs/MODEL.md, "The shape model and its gravity".
//!
//! ```no_run
//! # use touchdown::shape::*;
//! # fn main() -> Result<(), ShapeError> {
//! let mesh = read_shape(std::path::Path::new("ver64q.tab"), 1000.0)?.check()?;
//! let body = Polyhedron::new(mesh, 1900.0)?;
//! let omega = 2.0 * std::f64::consts::PI / (12.132 * 3600.0);
//! let sites = facets(&body, [0.0, 0.0, 1.0], omega);
//! # Ok(()) }
//! ```

mod error;
mod facets;
mod gravity;
mod icq;
mod intersect;
mod mesh;
mod obj;
mod plate;
mod read;
mod roughness;
mod tree;
mod vec3;

pub use error::ShapeError;
pub use facets::{
    EXACT_UP_TO, FacetGravity, GravitySum, centrifugal, facet_gravity, facets, facets_told,
    latitude_longitude, slope_deg, spin_frame, tree_facets, unit_axis,
};
pub use gravity::{Field, G, Polyhedron};
pub use icq::{parse_icq, read_icq};
pub use intersect::{PAIRS_AT_LEAST, PAIRS_PER_FACET};
pub use mesh::{CheckedMesh, DEGENERATE_AREA, Edge, FacetGeometry, MAX_FACETS, MAX_VERTICES, Mesh};
pub use obj::{MAX_LINE_BYTES, parse_obj, read_obj};
pub use plate::{parse_plate, read_plate};
pub use read::{parse_shape, read_shape};
pub use roughness::roughness_deg;
pub use tree::{FacetTree, LEAF, OPENING, ORDER};
