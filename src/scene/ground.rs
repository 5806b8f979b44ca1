//! The surface drawn under a trace: a patch of nodes around the CG's path, on the plane or
//! on the terrain tile the sample landed on.

use super::read::Scene;
use glam::DVec3;

/// Most nodes of a ground patch along either side.
const MAX_SIDE_NODES: usize = 2000;

/// A patch of the surface: node `(i, j)` at `origin + i spacing u + j spacing v` plus
/// `heights[j nu + i]` along the normal (no heights: the plane).
#[derive(Debug, Clone)]
pub struct Ground {
    /// Node `(0, 0)` in I.
    pub origin: DVec3,
    /// The surface's first tangent (along which `i` counts).
    pub u: DVec3,
    /// The surface's second tangent (along which `j` counts).
    pub v: DVec3,
    /// The surface's unit normal.
    pub normal: DVec3,
    /// Distance between neighbouring nodes, m.
    pub spacing_m: f64,
    /// Nodes along `u`.
    pub nu: usize,
    /// Nodes along `v`.
    pub nv: usize,
    /// Height of every node along the normal, m (none on a plane).
    pub heights: Option<Vec<f64>>,
}

impl Ground {
    /// Node `(i, j)` in I.
    #[must_use]
    pub fn node(&self, i: usize, j: usize) -> DVec3 {
        let h = self.heights.as_ref().map_or(0.0, |h| h[j * self.nu + i]);
        self.origin
            + self.u * (i as f64 * self.spacing_m)
            + self.v * (j as f64 * self.spacing_m)
            + self.normal * h
    }
}

impl Scene {
    /// The surface under the CG's path and `margin_m` around it, with nodes `spacing_m`
    /// apart (wider where the patch would pass `max_nodes` nodes, or `MAX_SIDE_NODES` along
    /// a side). Rows whose CG is not finite (a diverged sample's last) are left out.
    #[must_use]
    pub fn ground(&self, margin_m: f64, spacing_m: f64, max_nodes: usize) -> Ground {
        let s = &self.surface;
        let (mut lo, mut hi) = ([-margin_m; 2], [margin_m; 2]);
        let mut first = true;
        for p in self.trace.cg_path().into_iter().filter(|p| p.is_finite()) {
            for (k, axis) in [s.tangent_u, s.tangent_v].iter().enumerate() {
                let c = axis.dot(p);
                if first {
                    (lo[k], hi[k]) = (c - margin_m, c + margin_m);
                } else {
                    lo[k] = lo[k].min(c - margin_m);
                    hi[k] = hi[k].max(c + margin_m);
                }
            }
            first = false;
        }
        let side = |k: usize, spacing: f64| (hi[k] - lo[k]) / spacing + 2.0;
        let mut spacing = spacing_m;
        while side(0, spacing) * side(1, spacing) > max_nodes as f64
            || side(0, spacing).max(side(1, spacing)) > MAX_SIDE_NODES as f64
        {
            spacing *= 2.0;
        }
        // Nodes on whole multiples of the spacing, so that grid lines fall on whole metres.
        let snap = |x: f64| (x / spacing).floor() * spacing;
        let (u0, v0) = (snap(lo[0]), snap(lo[1]));
        let nu = ((hi[0] - u0) / spacing).ceil() as usize + 1;
        let nv = ((hi[1] - v0) / spacing).ceil() as usize + 1;
        let origin = s.tangent_u * u0 + s.tangent_v * v0;
        let heights = self.model.terrain.as_ref().map(|terrain| {
            let mut h = Vec::with_capacity(nu * nv);
            for j in 0..nv {
                for i in 0..nu {
                    let p = origin
                        + s.tangent_u * (i as f64 * spacing)
                        + s.tangent_v * (j as f64 * spacing);
                    h.push(s.height(Some(terrain), p).0);
                }
            }
            h
        });
        Ground {
            origin,
            u: s.tangent_u,
            v: s.tangent_v,
            normal: s.normal,
            spacing_m: spacing,
            nu,
            nv,
            heights,
        }
    }
}
