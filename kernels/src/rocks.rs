//! Rocks on the ground: rigid hemispheres sitting on the local surface, in square periodic
//! tiles (MODEL.md section 4, "Rocks"), and the geometry of a spherical footpad meeting one.
//!
//! A tile is divided into a grid of square cells; each cell lists (by index) every rock whose
//! disc's bounding square overlaps it, wrapped across the tile's edges, so a lookup reads
//! only the few cells under the footpad and a rock across an edge is found from either side.
//! Every rock carries the abundance at or above which it exists (its `threshold`): the tiles
//! are built once for the largest abundance a scenario draws (by the `touchdown` crate, which
//! owns the random numbers), and a sample of a smaller abundance only compares.

use crate::lane::{Lane, MAX_LANES};
use std::sync::Arc;

/// The penetration `Rocks::contact` returns where no rock present touches the footpad.
pub const NO_ROCK: f64 = f64::NEG_INFINITY;

/// A rock: a hemisphere whose centre lies on the local ground at `(u_m, v_m)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rock {
    /// Centre along the tile's first tangent axis, in `[0, tile_size_m)`, m.
    pub u_m: f64,
    /// Centre along the tile's second tangent axis, in `[0, tile_size_m)`, m.
    pub v_m: f64,
    /// Radius of the hemisphere (half the diameter; also its height), m.
    pub radius_m: f64,
    /// The rock abundance `k` at or above which the rock exists.
    pub threshold: f64,
}

/// Precomputed rock tiles. The rocks and the cells are shared: a clone costs a reference
/// count, not the tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct Rocks {
    tile_size_m: f64,
    /// `1 / tile_size_m`, so that a lookup needs no division.
    inverse_tile_size_per_m: f64,
    /// Cells per tile side.
    cells: usize,
    /// `cells / tile_size_m`, the inverse of a cell's side.
    inverse_cell_per_m: f64,
    /// Every rock once, tile after tile.
    rocks: Arc<[Rock]>,
    /// Where each tile's rocks start in `rocks`, and the end (`tiles + 1` entries).
    tile_start: Arc<[u32]>,
    /// Where each cell's entries start in `cell_rocks` (tile, then row `v`, then column
    /// `u`), and the end (`tiles * cells * cells + 1` entries).
    cell_start: Arc<[u32]>,
    /// The rocks (indices into `rocks`) overlapping each cell, cell after cell.
    cell_rocks: Arc<[u32]>,
    top_m: f64,
}

/// A rock's disc is entered into the cells of its bounding square widened by this much, so
/// that rounding at a cell's or the tile's edge never hides a rock touching a footpad there.
const MARGIN_M: f64 = 1e-9;

impl Rocks {
    /// Tiles of side `tile_size_m`, each a grid of `cells` x `cells` cells, from the rocks
    /// of each tile (`rocks[tile]`).
    ///
    /// # Panics
    /// If there is no tile, `cells` is 0, the tile size is not positive and finite, or a
    /// rock lies outside its tile, is not positive or wider than half the tile (its radius
    /// above a quarter of it), or has a NaN threshold; or the rocks overflow the indices.
    #[must_use]
    pub fn new(tile_size_m: f64, cells: usize, rocks: Vec<Vec<Rock>>) -> Rocks {
        assert!(!rocks.is_empty() && cells >= 1);
        assert!(tile_size_m > 0.0 && tile_size_m.is_finite());
        let inverse_cell_per_m = cells as f64 / tile_size_m;
        let all: Vec<Rock> = rocks.iter().flatten().copied().collect();
        assert!(u32::try_from(all.len()).is_ok(), "fewer than 2^32 rocks");
        let mut tile_start = vec![0u32];
        for list in &rocks {
            tile_start.push(tile_start[tile_start.len() - 1] + list.len() as u32);
        }
        let mut tile_of = Vec::with_capacity(all.len());
        for (tile, list) in rocks.iter().enumerate() {
            for rock in list {
                assert!((0.0..tile_size_m).contains(&rock.u_m));
                assert!((0.0..tile_size_m).contains(&rock.v_m));
                assert!(rock.radius_m > 0.0 && rock.radius_m <= 0.25 * tile_size_m);
                assert!(!rock.threshold.is_nan());
                tile_of.push(tile);
            }
        }
        // The cells each rock covers, counted, then filled in (a counting sort by cell).
        let covered = |index: usize, each: &mut dyn FnMut(usize)| {
            let rock = &all[index];
            let reach = rock.radius_m + MARGIN_M;
            let span = |x: f64| {
                let lo = ((x - reach) * inverse_cell_per_m).floor() as i64;
                let hi = ((x + reach) * inverse_cell_per_m).floor() as i64;
                // A disc at most half a tile wide meets no cell twice, but a tile of one or
                // two cells is met from both sides: each cell once.
                lo..=hi.min(lo + cells as i64 - 1)
            };
            for j in span(rock.v_m) {
                let row = (tile_of[index] * cells + j.rem_euclid(cells as i64) as usize) * cells;
                for i in span(rock.u_m) {
                    each(row + i.rem_euclid(cells as i64) as usize);
                }
            }
        };
        let mut cell_start = vec![0u32; rocks.len() * cells * cells + 1];
        for index in 0..all.len() {
            covered(index, &mut |cell| cell_start[cell + 1] += 1);
        }
        for cell in 0..cell_start.len() - 1 {
            cell_start[cell + 1] = cell_start[cell]
                .checked_add(cell_start[cell + 1])
                .expect("fewer than 2^32 entries");
        }
        let mut next = cell_start.clone();
        let mut cell_rocks = vec![0u32; cell_start[cell_start.len() - 1] as usize];
        for index in 0..all.len() {
            covered(index, &mut |cell| {
                cell_rocks[next[cell] as usize] = index as u32;
                next[cell] += 1;
            });
        }
        let top_m = all.iter().map(|r| r.radius_m).fold(0.0, f64::max);
        Rocks {
            tile_size_m,
            inverse_tile_size_per_m: 1.0 / tile_size_m,
            cells,
            inverse_cell_per_m,
            rocks: all.into(),
            tile_start: tile_start.into(),
            cell_start: cell_start.into(),
            cell_rocks: cell_rocks.into(),
            top_m,
        }
    }

    /// Number of tiles.
    #[must_use]
    pub fn tiles(&self) -> usize {
        self.tile_start.len() - 1
    }

    /// Side of a tile, m.
    #[must_use]
    pub fn tile_size_m(&self) -> f64 {
        self.tile_size_m
    }

    /// Cells per tile side.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.cells
    }

    /// The largest rock radius of all tiles (0 without rocks): no rock is higher, m.
    #[must_use]
    pub fn top_m(&self) -> f64 {
        self.top_m
    }

    /// The rocks of `tile`, each once (of every abundance: see `Rock::threshold`).
    #[must_use]
    pub fn rocks(&self, tile: usize) -> &[Rock] {
        &self.rocks[self.tile_start[tile] as usize..self.tile_start[tile + 1] as usize]
    }

    /// Bytes held by the tiles (rocks, cell lists and offsets).
    #[must_use]
    pub fn bytes(&self) -> usize {
        self.rocks.len() * size_of::<Rock>()
            + (self.tile_start.len() + self.cell_start.len() + self.cell_rocks.len())
                * size_of::<u32>()
    }

    /// The deepest contact of a spherical footpad with the rocks of `tile` present at
    /// `abundance` (`threshold <= abundance`), as `(penetration_m, normal_u, normal_v,
    /// normal_n)` in the tile's frame (`n` the local ground's normal, up).
    ///
    /// The footpad's lowest point is at `(u, v, height_m)` (any `u`, `v`: the tile repeats),
    /// its centre `pad_radius_m` above it; a rock of radius `R` is a hemisphere centred on
    /// the ground plane. The penetration is `R + pad_radius_m - |c|` and the normal `c / |c|`,
    /// with `c` the footpad's centre less the rock's centre (`(0, 0, 1)` where they meet);
    /// a centre below the plane uses the same formula. Where no rock present touches the
    /// footpad (penetration below 0), `(NO_ROCK, 0, 0, 1)`. `pad_radius_m` must be at most a
    /// quarter of the tile. No allocation; square roots only for rocks in contact.
    #[inline(always)]
    #[must_use]
    pub fn contact(
        &self,
        tile: usize,
        u: f64,
        v: f64,
        height_m: f64,
        pad_radius_m: f64,
        abundance: f64,
    ) -> (f64, f64, f64, f64) {
        // No rock reaches above its radius, and none above the largest.
        if height_m > self.top_m {
            return (NO_ROCK, 0.0, 0.0, 1.0);
        }
        let size = self.tile_size_m;
        let (u, v) = (
            u - size * (u * self.inverse_tile_size_per_m).floor(),
            v - size * (v * self.inverse_tile_size_per_m).floor(),
        );
        let n_centre = height_m + pad_radius_m;
        let cells = self.cells as i64;
        let inv = self.inverse_cell_per_m;
        let (i_lo, i_hi) = (
            ((u - pad_radius_m) * inv).floor() as i64,
            ((u + pad_radius_m) * inv).floor() as i64,
        );
        let (j_lo, j_hi) = (
            ((v - pad_radius_m) * inv).floor() as i64,
            ((v + pad_radius_m) * inv).floor() as i64,
        );
        let mut best = (NO_ROCK, 0.0, 0.0, 1.0);
        for j in j_lo..=j_hi {
            let row = (tile * self.cells + j.rem_euclid(cells) as usize) * self.cells;
            for i in i_lo..=i_hi {
                let cell = row + i.rem_euclid(cells) as usize;
                let entries = self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize;
                for &index in &self.cell_rocks[entries] {
                    let rock = &self.rocks[index as usize];
                    if rock.threshold > abundance {
                        continue;
                    }
                    let du = nearest(u - rock.u_m, size);
                    let dv = nearest(v - rock.v_m, size);
                    let reach = rock.radius_m + pad_radius_m;
                    let distance2 = du * du + dv * dv + n_centre * n_centre;
                    if distance2 > reach * reach {
                        continue;
                    }
                    let distance = distance2.sqrt();
                    let penetration = reach - distance;
                    if penetration > best.0 {
                        best = if distance > 0.0 {
                            let inverse = 1.0 / distance;
                            (penetration, du * inverse, dv * inverse, n_centre * inverse)
                        } else {
                            (penetration, 0.0, 0.0, 1.0)
                        };
                    }
                }
            }
        }
        best
    }
}

/// `d`, a difference of two coordinates in `[0, size)`, as the nearest of its periodic
/// images: in `[-size / 2, size / 2]`.
#[inline(always)]
fn nearest(d: f64, size: f64) -> f64 {
    if d > 0.5 * size {
        d - size
    } else if d < -0.5 * size {
        d + size
    } else {
        d
    }
}

/// `Rocks::contact` under every lane, each lane on its own tile: one scalar lookup per lane
/// (the rocks of different lanes are far apart in memory, as the terrain's nodes are).
#[inline(always)]
#[must_use]
pub fn contact_lanes<L: Lane>(
    rocks: &Rocks,
    tile: &[usize; MAX_LANES],
    u: L,
    v: L,
    height: L,
    pad_radius: L,
    abundance: L,
) -> (L, L, L, L) {
    let (mut p, mut nu, mut nv, mut nn) = (L::ZERO, L::ZERO, L::ZERO, L::ZERO);
    for (i, &tile) in tile.iter().enumerate().take(L::LANES) {
        let (pi, nui, nvi, nni) = rocks.contact(
            tile,
            u.lane(i),
            v.lane(i),
            height.lane(i),
            pad_radius.lane(i),
            abundance.lane(i),
        );
        p.set_lane(i, pi);
        nu.set_lane(i, nui);
        nv.set_lane(i, nvi);
        nn.set_lane(i, nni);
    }
    (p, nu, nv, nn)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rock(u_m: f64, v_m: f64, radius_m: f64, threshold: f64) -> Rock {
        Rock {
            u_m,
            v_m,
            radius_m,
            threshold,
        }
    }

    /// One tile of 4 m in 8 cells of 0.5 m with one rock of radius 0.3 m at (1.25, 2.25).
    fn one_rock(threshold: f64) -> Rocks {
        Rocks::new(4.0, 8, vec![vec![rock(1.25, 2.25, 0.3, threshold)]])
    }

    #[test]
    fn a_footpad_on_a_rocks_top_rests_at_its_height() {
        let rocks = one_rock(0.05);
        assert_eq!(rocks.top_m(), 0.3);
        // The lowest point of a footpad of 0.1 m directly above the centre at the rock's
        // height: just touching, pushed straight up.
        let (p, nu, nv, nn) = rocks.contact(0, 1.25, 2.25, 0.3, 0.1, 0.07);
        assert_eq!((p, nu, nv, nn), (0.0, 0.0, 0.0, 1.0));
        // 2 cm lower it penetrates by 2 cm, still along n.
        let (p, nu, nv, nn) = rocks.contact(0, 1.25, 2.25, 0.28, 0.1, 0.07);
        assert!((p - 0.02).abs() < 1e-15 && nu == 0.0 && nv == 0.0 && nn == 1.0);
        // 1 mm higher it is clear.
        assert_eq!(rocks.contact(0, 1.25, 2.25, 0.301, 0.1, 0.07).0, NO_ROCK);
    }

    #[test]
    fn a_footpad_beside_a_rock_strikes_it_with_its_side() {
        // A footpad of radius rho at ground level (height 0, centre at n = rho) moving along
        // u towards the rock first touches it where the centres are R + rho apart: at
        // du = sqrt((R + rho)^2 - rho^2), with the normal's n component rho / (R + rho).
        let rocks = one_rock(0.0);
        let (r, rho): (f64, f64) = (0.3, 0.1);
        let du = ((r + rho) * (r + rho) - rho * rho).sqrt();
        let (p, nu, nv, nn) = rocks.contact(0, 1.25 - du, 2.25, 0.0, rho, 0.0);
        assert!(p.abs() < 1e-15, "penetration {p}");
        assert!((nn - rho / (r + rho)).abs() < 1e-15, "n component {nn}");
        assert!((nu + du / (r + rho)).abs() < 1e-15 && nv == 0.0);
        // 1 cm closer: 1 cm less apart in u, the closed form's penetration.
        let (p, ..) = rocks.contact(0, 1.25 - du + 0.01, 2.25, 0.0, rho, 0.0);
        let expected = r + rho - ((du - 0.01).powi(2) + rho * rho).sqrt();
        assert!((p - expected).abs() < 1e-15 && p > 0.0);
    }

    #[test]
    fn a_rock_across_the_tile_edge_is_found_from_the_other_side() {
        // A rock at (0.125, 3.875) reaches across u = 0 and v = 4 m onto the tile's far
        // sides.
        let rocks = Rocks::new(4.0, 8, vec![vec![rock(0.125, 3.875, 0.3, 0.0)]]);
        let near = rocks.contact(0, 0.125, 3.875, 0.2, 0.1, 0.1);
        assert!((near.0 - 0.1).abs() < 1e-15 && near.3 == 1.0);
        // From the far side of both edges, 0.25 m from the centre in u and in v.
        let far = rocks.contact(0, 3.875, 0.125, 0.0, 0.1, 0.1);
        let centre = (0.25f64 * 0.25 * 2.0 + 0.01).sqrt();
        assert!(
            (far.0 - (0.4 - centre)).abs() < 1e-15 && far.0 > 0.0,
            "{far:?}"
        );
        assert!((far.1 + 0.25 / centre).abs() < 1e-15 && (far.2 - 0.25 / centre).abs() < 1e-15);
        // One tile further, and one tile back, the same point.
        assert_eq!(rocks.contact(0, 7.875, 4.125, 0.0, 0.1, 0.1), far);
        assert_eq!(rocks.contact(0, -0.125, -3.875, 0.0, 0.1, 0.1), far);
        assert_eq!(rocks.contact(0, 4.125, 7.875, 0.2, 0.1, 0.1), near);
    }

    #[test]
    fn a_rock_above_the_abundance_is_absent() {
        let rocks = one_rock(0.05);
        assert_eq!(
            rocks.contact(0, 1.25, 2.25, 0.0, 0.1, 0.049_999),
            (NO_ROCK, 0.0, 0.0, 1.0)
        );
        assert!(rocks.contact(0, 1.25, 2.25, 0.0, 0.1, 0.05).0 > 0.0);
    }

    /// splitmix64's next value in [0, 1).
    fn next(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The deepest contact over every rock of the tile and its eight neighbours' images.
    fn brute_force(list: &[Rock], size: f64, u: f64, v: f64, h: f64, rho: f64, k: f64) -> f64 {
        let mut best = NO_ROCK;
        for rock in list.iter().filter(|r| r.threshold <= k) {
            for (su, sv) in (-1..=1).flat_map(|a| (-1..=1).map(move |b| (a, b))) {
                let du = u - (rock.u_m + su as f64 * size);
                let dv = v - (rock.v_m + sv as f64 * size);
                let d = (du * du + dv * dv + (h + rho) * (h + rho)).sqrt();
                let p = rock.radius_m + rho - d;
                if p >= 0.0 {
                    best = best.max(p);
                }
            }
        }
        best
    }

    #[test]
    fn the_deepest_contact_matches_a_scan_of_every_rock() {
        // Two tiles of 3 m, 400 rocks each (a dense field, so that pads meet several), cells
        // of 0.375 m smaller than the largest rocks (radius up to 0.4 m): rocks span cells.
        let mut s = 7u64;
        let size = 3.0;
        let tiles: Vec<Vec<Rock>> = (0..2)
            .map(|_| {
                (0..400)
                    .map(|_| {
                        let (u, v) = (next(&mut s) * size, next(&mut s) * size);
                        rock(u, v, 0.02 + 0.38 * next(&mut s), next(&mut s))
                    })
                    .collect()
            })
            .collect();
        let rocks = Rocks::new(size, 8, tiles.clone());
        let mut hits = 0;
        for _ in 0..4000 {
            let tile = (next(&mut s) * 2.0) as usize;
            let (u, v) = (next(&mut s) * 9.0 - 3.0, next(&mut s) * 9.0 - 3.0);
            let (h, rho, k) = (
                next(&mut s) * 0.5 - 0.1,
                0.05 + 0.2 * next(&mut s),
                next(&mut s),
            );
            let (uw, vw) = (u.rem_euclid(size), v.rem_euclid(size));
            let expected = brute_force(&tiles[tile], size, uw, vw, h, rho, k);
            let (p, nu, nv, nn) = rocks.contact(tile, u, v, h, rho, k);
            // Both wrap the footpad onto the tile; they differ by its rounding (1e-15 m).
            assert!(
                (p - expected).abs() < 1e-12 || p == expected,
                "{p} against {expected}"
            );
            assert!((nu * nu + nv * nv + nn * nn - 1.0).abs() < 1e-12);
            hits += usize::from(p >= 0.0);
        }
        assert!(hits > 1000, "{hits} contacts");
    }

    #[test]
    fn lanes_look_up_each_lane_on_its_tile() {
        use wide::f64x8;
        let rocks = Rocks::new(
            4.0,
            8,
            vec![
                vec![rock(1.0, 1.0, 0.3, 0.0)],
                vec![rock(3.0, 3.0, 0.2, 0.0)],
            ],
        );
        let mut tile = [0; MAX_LANES];
        tile[1] = 1;
        let u = f64x8::from([1.0, 3.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
        let (p, _, _, nn) = contact_lanes(
            &rocks,
            &tile,
            u,
            u,
            f64x8::splat(0.1),
            f64x8::splat(0.1),
            f64x8::splat(0.1),
        );
        assert!((p.lane(0) - 0.2).abs() < 1e-15 && (p.lane(1) - 0.1).abs() < 1e-15);
        assert!((p.lane(7) - 0.2).abs() < 1e-15 && nn.lane(1) == 1.0);
    }
}
