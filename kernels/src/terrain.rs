//! Rough terrain: square periodic tiles of node heights, bilinear between nodes.
//!
//! Heights are offsets along the slope normal at nodes of a square grid laid out along the
//! slope's tangent axes `(u, v)`. Tiles are periodic, so any offset and any distance slid
//! stays on the tile. The tiles are built once per sweep (by the `touchdown` crate, which
//! owns the random numbers) and shared read-only by every lane.

use crate::lane::{Lane, MAX_LANES};
use std::sync::Arc;

/// Precomputed terrain tiles. The heights are shared: a clone (the kernels' parameters of
/// each worker, the model of each sample) costs a reference count, not the tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct Terrain {
    nodes: usize,
    spacing_m: f64,
    /// `1 / spacing_m`, so that a lookup needs no division. (A division here, hoisted by
    /// the compiler out of the kernels' `match` on the terrain, ran on whatever bytes an
    /// absent terrain left in its place, denormals among them: a microcode assist of a
    /// hundred cycles per step on a flat surface.)
    inverse_spacing_per_m: f64,
    heights_m: Arc<[f64]>,
    height_max_m: f64,
    /// Factor on every height (and slope): 1 for the tiles as built; a sample that draws
    /// its roughness scales the tiles built for the largest (`scaled`).
    scale: f64,
}

impl Terrain {
    /// Tiles of `nodes` x `nodes` heights each, row-major (`v` rows of `u` columns),
    /// tile after tile.
    ///
    /// # Panics
    /// If `heights_m` does not hold a whole number of tiles, or `nodes < 2`.
    #[must_use]
    pub fn new(nodes: usize, spacing_m: f64, heights_m: Vec<f64>) -> Terrain {
        assert!(
            nodes >= 2 && !heights_m.is_empty() && heights_m.len().is_multiple_of(nodes * nodes)
        );
        let height_max_m = heights_m.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Terrain {
            nodes,
            spacing_m,
            inverse_spacing_per_m: 1.0 / spacing_m,
            heights_m: heights_m.into(),
            height_max_m,
            scale: 1.0,
        }
    }

    /// These tiles with every height multiplied by `scale` (the tiles themselves shared).
    #[must_use]
    pub fn scaled(&self, scale: f64) -> Terrain {
        Terrain {
            scale,
            ..self.clone()
        }
    }

    /// The factor on the heights of the tiles as built (`scaled`).
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Number of tiles.
    #[must_use]
    pub fn tiles(&self) -> usize {
        self.heights_m.len() / (self.nodes * self.nodes)
    }

    /// Nodes per tile side.
    #[must_use]
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Distance between nodes, m.
    #[must_use]
    pub fn spacing_m(&self) -> f64 {
        self.spacing_m
    }

    /// The highest node of all tiles (scaled): no point of the surface is higher.
    #[must_use]
    pub fn height_max_m(&self) -> f64 {
        self.height_max_m * self.scale
    }

    /// All heights as built (not scaled), tile after tile.
    #[must_use]
    pub fn heights_m(&self) -> &[f64] {
        &self.heights_m
    }

    /// Height and its slopes `(h, dh/du, dh/dv)` at tangent coordinates `(u, v)` of `tile`,
    /// scaled (`scaled`).
    #[inline(always)]
    #[must_use]
    pub fn height(&self, tile: usize, u: f64, v: f64) -> (f64, f64, f64) {
        let (h, dh_du, dh_dv) = self.unit_height(tile, u, v);
        (h * self.scale, dh_du * self.scale, dh_dv * self.scale)
    }

    /// `height` of the tiles as built: the kernels scale it per lane.
    #[inline(always)]
    #[must_use]
    pub fn unit_height(&self, tile: usize, u: f64, v: f64) -> (f64, f64, f64) {
        let n = self.nodes;
        let inv = self.inverse_spacing_per_m;
        let (fu, fv) = (u * inv, v * inv);
        let (cu, cv) = (fu.floor(), fv.floor());
        let (a, b) = (fu - cu, fv - cv);
        let i0 = (cu as i64).rem_euclid(n as i64) as usize;
        let j0 = (cv as i64).rem_euclid(n as i64) as usize;
        let (i1, j1) = ((i0 + 1) % n, (j0 + 1) % n);
        let t = &self.heights_m[tile * n * n..(tile + 1) * n * n];
        let (h00, h10, h01, h11) = (
            t[j0 * n + i0],
            t[j0 * n + i1],
            t[j1 * n + i0],
            t[j1 * n + i1],
        );
        let h =
            h00 * (1.0 - a) * (1.0 - b) + h10 * a * (1.0 - b) + h01 * (1.0 - a) * b + h11 * a * b;
        let dh_du = ((h10 - h00) * (1.0 - b) + (h11 - h01) * b) * inv;
        let dh_dv = ((h01 - h00) * (1.0 - a) + (h11 - h10) * a) * inv;
        (h, dh_du, dh_dv)
    }
}

/// Height and slopes of the tiles as built under every lane (`Terrain::unit_height`; the
/// caller scales them): one scalar lookup per lane (the nodes of different lanes are far
/// apart in memory, so a gather is all SIMD could do).
#[inline(always)]
#[must_use]
pub fn height_lanes<L: Lane>(
    terrain: &Terrain,
    tile: &[usize; MAX_LANES],
    u: L,
    v: L,
) -> (L, L, L) {
    let (mut h, mut du, mut dv) = (L::ZERO, L::ZERO, L::ZERO);
    for (i, &tile) in tile.iter().enumerate().take(L::LANES) {
        let (hi, dui, dvi) = terrain.unit_height(tile, u.lane(i), v.lane(i));
        h.set_lane(i, hi);
        du.set_lane(i, dui);
        dv.set_lane(i, dvi);
    }
    (h, du, dv)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_reproduces_a_plane_and_wraps() {
        // Heights of the plane h = 0.1 u + 0.2 v sampled on a 4 x 4 tile: inside the first
        // three cells bilinear interpolation is exact.
        let n = 4;
        let s = 0.5;
        let mut h = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                h[j * n + i] = 0.1 * i as f64 * s + 0.2 * j as f64 * s;
            }
        }
        let t = Terrain::new(n, s, h);
        let (z, du, dv) = t.height(0, 0.7, 1.1);
        assert!((z - (0.07 + 0.22)).abs() < 1e-12);
        assert!((du - 0.1).abs() < 1e-12 && (dv - 0.2).abs() < 1e-12);
        // One tile (2 m) further along u is the same point.
        assert_eq!(t.height(0, 2.7, 1.1), t.height(0, 0.7, 1.1));
        assert_eq!(t.height(0, -1.3, 1.1), t.height(0, 0.7, 1.1));
        assert_eq!(t.height_max_m(), 0.1 * 1.5 + 0.2 * 1.5);
    }
}
