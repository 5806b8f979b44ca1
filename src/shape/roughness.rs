//! Each facet's roughness: how far its neighbours' normals turn from its own, the relief
//! from facet to facet that the shape model resolves. Geometry only (no gravity, no spin);
//! reported by `touchdown site`, never simulated. docs/MODEL.md 13.1.

use super::mesh::CheckedMesh;
use super::vec3::{cross, dot, norm};

/// The angle between two unit normals, deg, in [0, 180]: `atan2(|a x b|, a . b)`, accurate
/// at small angles where `acos(a . b)` loses half its digits.
#[must_use]
fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b)).to_degrees()
}

/// Each facet's roughness, deg, in facet order: the root mean square of the angles between
/// its outward normal and the normals of the facets across its edges,
/// `sqrt((a_1^2 + a_2^2 + a_3^2) / 3)`. On a checked mesh (closed and manifold) every facet
/// has exactly three edges, each shared with one other facet; the edges' list of
/// [`CheckedMesh::edges`] gives them, so the cost is one pass over the edges.
///
/// On a smooth body it is about the facet-scale curvature (on a sphere of radius `R` meshed
/// with equilateral triangles of side `e`, `e / (sqrt(3) R)` radians: the angle the centre
/// sees between two neighbours' centroids); on a coarse or radar model it measures the
/// model's resolution as much as the surface.
#[must_use]
pub fn roughness_deg(mesh: &CheckedMesh) -> Vec<f64> {
    let geometry = mesh.facet_geometry();
    let mut sum = vec![0.0_f64; geometry.len()];
    let mut count = vec![0_u32; geometry.len()];
    for edge in mesh.edges() {
        let [f, g] = edge.facets.map(|x| x as usize);
        let (Some(a), Some(b)) = (geometry.get(f), geometry.get(g)) else {
            continue;
        };
        let angle = angle_deg(a.normal, b.normal);
        for k in [f, g] {
            sum[k] += angle * angle;
            count[k] += 1;
        }
    }
    // `count` is 3 for every facet of a checked mesh; dividing by it keeps the mean a mean
    // whatever happens, and a facet without edges (none exists) would be NaN.
    sum.iter()
        .zip(&count)
        .map(|(s, &n)| (s / f64::from(n)).sqrt())
        .collect()
}
