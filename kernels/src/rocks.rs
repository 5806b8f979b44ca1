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
    /// The largest radius (the height) of the rocks overlapping each cell, of every
    /// abundance (0 for a cell that none overlaps), cell after cell.
    cell_top_m: Arc<[f64]>,
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
        let cell_top_m: Vec<f64> = (0..cell_start.len() - 1)
            .map(|cell| {
                let entries = cell_start[cell] as usize..cell_start[cell + 1] as usize;
                cell_rocks[entries]
                    .iter()
                    .map(|&index| all[index as usize].radius_m)
                    .fold(0.0, f64::max)
            })
            .collect();
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
            cell_top_m: cell_top_m.into(),
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
            + self.cell_top_m.len() * size_of::<f64>()
    }

    /// A cell's column or row `i` as its index in `[0, cells)`: `i` lies within a quarter of
    /// a tile and a cell of the tile (a square of half-side at most a quarter of the tile
    /// about a point in `[0, tile_size_m]`), so one add or subtract wraps it (`rem_euclid`'s result, without
    /// its division).
    #[inline(always)]
    fn wrap(&self, i: i64) -> usize {
        let cells = self.cells as i64;
        debug_assert!((-cells..2 * cells).contains(&i));
        let i = if i < 0 {
            i + cells
        } else if i >= cells {
            i - cells
        } else {
            i
        };
        i as usize
    }

    /// The skin `contact_clear` reads beyond a footpad of `pad_radius_m`: `SKIN_M`, or
    /// less where the tile is too small for it (the lookup reads at most a quarter).
    #[inline(always)]
    #[must_use]
    pub fn skin_m(&self, pad_radius_m: f64) -> f64 {
        SKIN_M.min(0.25 * self.tile_size_m - pad_radius_m).max(0.0)
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
    /// footpad (penetration below 0), `(NO_ROCK, 0, 0, 1)`. Of two rocks at the same
    /// penetration, the first in `rocks(tile)`. `pad_radius_m` must be at most a quarter of
    /// the tile. No allocation; square roots only for rocks in contact.
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
        self.contact_clear(tile, u, v, height_m, pad_radius_m, abundance, 0.0)
            .0
    }

    /// `contact`, and how far the footpad is free to move before it can meet a rock
    /// present, m: the least gap `|c| - R - pad_radius_m` between the footpad's sphere and
    /// a rock's (the negated penetration: at most 0 in contact), and at most `skin_m`. The
    /// gap changes no faster than `(u, v, height_m)` moves, so while the footpad stays
    /// within that distance of `(u, v, height_m)` (in the tile's frame), `contact` finds no
    /// rock there. Rocks further than `skin_m` from the footpad's sphere are not read:
    /// `pad_radius_m + skin_m` must be at most a quarter of the tile.
    #[inline(always)]
    #[must_use]
    #[allow(clippy::too_many_arguments)]
    pub fn contact_clear(
        &self,
        tile: usize,
        u: f64,
        v: f64,
        height_m: f64,
        pad_radius_m: f64,
        abundance: f64,
        skin_m: f64,
    ) -> ((f64, f64, f64, f64), f64) {
        // No rock reaches above its radius, and none above the largest: the footpad's
        // centre is `height_m + pad_radius_m` above every rock's, so the gap is at least
        // `height_m - R`.
        if height_m > self.top_m {
            return ((NO_ROCK, 0.0, 0.0, 1.0), skin_m.min(height_m - self.top_m));
        }
        let size = self.tile_size_m;
        let (u, v) = (
            u - size * (u * self.inverse_tile_size_per_m).floor(),
            v - size * (v * self.inverse_tile_size_per_m).floor(),
        );
        let n_centre = height_m + pad_radius_m;
        let mut best = (NO_ROCK, 0.0, 0.0, 1.0);
        let mut best_index = u32::MAX;
        let mut free = skin_m;
        // A rock whose disc is further than `pad_radius_m + skin_m` from the footpad's
        // centre along one axis is in no cell read, and its gap is beyond `skin_m`.
        let (reach_m, inv) = (pad_radius_m + skin_m, self.inverse_cell_per_m);
        let (i_lo, i_hi) = (
            ((u - reach_m) * inv).floor() as i64,
            ((u + reach_m) * inv).floor() as i64,
        );
        let (j_lo, j_hi) = (
            ((v - reach_m) * inv).floor() as i64,
            ((v + reach_m) * inv).floor() as i64,
        );
        for j in j_lo..=j_hi {
            let row = (tile * self.cells + self.wrap(j)) * self.cells;
            for i in i_lo..=i_hi {
                let cell = row + self.wrap(i);
                // No rock of the cell reaches the footpad's lowest point.
                let above = height_m - self.cell_top_m[cell];
                if above > 0.0 {
                    free = free.min(above);
                    continue;
                }
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
                    let near = reach + skin_m;
                    if distance2 > near * near {
                        continue;
                    }
                    let distance = distance2.sqrt();
                    free = free.min(distance - reach);
                    if distance2 > reach * reach {
                        continue;
                    }
                    let penetration = reach - distance;
                    if penetration > best.0 || (penetration == best.0 && index < best_index) {
                        best_index = index;
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
        (best, free)
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

/// How far beyond a footpad's sphere `contact_lanes` reads the rocks, m: until the footpad
/// has moved about that far (or to the nearest rock, if nearer), it is not read again.
pub const SKIN_M: f64 = 0.05;

/// What `contact_lanes` remembers of one leg, per lane: where the footpad was (`contact`'s
/// `u`, `v` and `height_m`) when the rocks were last read for it, and how far from there it
/// is free to move and meet no rock (`Rocks::contact_clear`), less 1 % and 1 micrometre for
/// the rounding of the lanes' arithmetic (in f32 too); negative where they must be read at
/// the next step.
#[derive(Debug, Clone, Copy)]
#[allow(missing_docs)]
pub struct RockClearance<L: Lane> {
    pub u_m: L,
    pub v_m: L,
    pub height_m: L,
    pub free_m: L,
}

impl<L: Lane> RockClearance<L> {
    /// Nothing remembered: every lane reads the rocks at its next step.
    #[must_use]
    pub fn new() -> RockClearance<L> {
        RockClearance {
            u_m: L::ZERO,
            v_m: L::ZERO,
            height_m: L::ZERO,
            free_m: L::splat(-1.0),
        }
    }

    /// Lane `i` reads the rocks at its next step (a new sample, or a moved origin).
    pub fn forget(&mut self, i: usize) {
        self.free_m.set_lane(i, -1.0);
    }
}

impl<L: Lane> Default for RockClearance<L> {
    fn default() -> Self {
        Self::new()
    }
}

/// `Rocks::contact` under every lane, each lane on its own tile: one scalar lookup per lane
/// (the rocks of different lanes are far apart in memory, as the terrain's nodes are), but
/// only for lanes whose footpad has left the room `clear` remembers; the others meet no
/// rock, as the lookup would have found (`Rocks::contact_clear`): `(NO_ROCK, 0, 0, 1)`.
/// (The reference looks up at every step; reading less is this kernel's, with the same
/// results.)
#[inline(always)]
#[must_use]
#[allow(clippy::too_many_arguments)]
pub fn contact_lanes<L: Lane>(
    rocks: &Rocks,
    tile: &[usize; MAX_LANES],
    u: L,
    v: L,
    height: L,
    pad_radius: L,
    abundance: L,
    clear: &mut RockClearance<L>,
) -> (L, L, L, L) {
    let (du, dv, dh) = (u - clear.u_m, v - clear.v_m, height - clear.height_m);
    let moved_squared = du * du + dv * dv + dh * dh;
    let free = clear.free_m;
    // (A NaN position reads the rocks, as the reference does at every step.)
    let stays = moved_squared.simd_lt(free * free) & free.simd_gt(L::ZERO);
    let mut read: u32 = !crate::lane::Mask::to_bitmask(stays) & (u32::MAX >> (32 - L::LANES));
    let (mut p, mut nu, mut nv, mut nn) = (L::splat(NO_ROCK), L::ZERO, L::ZERO, L::splat(1.0));
    while read != 0 {
        let i = read.trailing_zeros() as usize;
        read &= read - 1;
        let (u, v, height, pad_radius) = (u.lane(i), v.lane(i), height.lane(i), pad_radius.lane(i));
        let skin = rocks.skin_m(pad_radius);
        let ((pi, nui, nvi, nni), free) =
            rocks.contact_clear(tile[i], u, v, height, pad_radius, abundance.lane(i), skin);
        p.set_lane(i, pi);
        nu.set_lane(i, nui);
        nv.set_lane(i, nvi);
        nn.set_lane(i, nni);
        clear.u_m.set_lane(i, u);
        clear.v_m.set_lane(i, v);
        clear.height_m.set_lane(i, height);
        clear.free_m.set_lane(i, 0.99 * free - 1e-6);
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

    /// `tiles` tiles of side `size`, `count` rocks each at uniform places, radii uniform in
    /// `[radius_min, radius_min + radius_span)`, thresholds uniform in `[0, 1)`.
    fn field(
        s: &mut u64,
        tiles: usize,
        count: usize,
        size: f64,
        radius_min: f64,
        radius_span: f64,
    ) -> Vec<Vec<Rock>> {
        (0..tiles)
            .map(|_| {
                (0..count)
                    .map(|_| {
                        let (u, v) = (next(s) * size, next(s) * size);
                        rock(u, v, radius_min + radius_span * next(s), next(s))
                    })
                    .collect()
            })
            .collect()
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
        let tiles = field(&mut s, 2, 400, size, 0.02, 0.38);
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
    fn the_free_distance_is_the_gap_to_the_nearest_rock_up_to_the_skin() {
        // A field sparse enough for footpads clear of every rock: the free distance is the
        // least gap `|c| - R - rho` between the footpad's sphere and a rock present's
        // (brute force over every rock and its periodic images), capped at the skin; the
        // lowest point's height above the highest rock when higher than all of them.
        let mut s = 11u64;
        let size = 3.0;
        let tiles = field(&mut s, 2, 25, size, 0.02, 0.18);
        let rocks = Rocks::new(size, 8, tiles.clone());
        let (mut capped, mut gaps, mut touching) = (0, 0, 0);
        for _ in 0..4000 {
            let tile = (next(&mut s) * 2.0) as usize;
            let (u, v) = (next(&mut s) * 9.0 - 3.0, next(&mut s) * 9.0 - 3.0);
            let (h, rho, k) = (
                next(&mut s) * 0.3 - 0.02,
                0.05 + 0.1 * next(&mut s),
                next(&mut s),
            );
            let skin = 0.2 * next(&mut s);
            let (uw, vw) = (u.rem_euclid(size), v.rem_euclid(size));
            let gap = tiles[tile]
                .iter()
                .filter(|r| r.threshold <= k)
                .map(|r| {
                    let (du, dv) = (nearest(uw - r.u_m, size), nearest(vw - r.v_m, size));
                    (du * du + dv * dv + (h + rho) * (h + rho)).sqrt() - r.radius_m - rho
                })
                .fold(f64::INFINITY, f64::min);
            let (contact, free) = rocks.contact_clear(tile, u, v, h, rho, k, skin);
            assert_eq!(contact, rocks.contact(tile, u, v, h, rho, k));
            if h > rocks.top_m() {
                assert_eq!(free, skin.min(h - rocks.top_m()));
                assert!(free <= gap + 1e-12);
            } else if gap >= skin {
                assert!(
                    free <= skin && free >= (h - rocks.top_m()).min(skin),
                    "{free} {gap}"
                );
                capped += 1;
            } else {
                assert!(
                    (free - gap).abs() < 1e-12 || free <= gap,
                    "{free} against {gap}"
                );
                gaps += usize::from((free - gap).abs() < 1e-12);
                touching += usize::from(gap <= 0.0);
            }
        }
        assert!(
            capped > 200 && gaps > 200 && touching > 20,
            "{capped} {gaps} {touching}"
        );
    }

    /// Footpads walking through a dense field (and now and then jumping), each step looked
    /// up with `contact_lanes`'s memory and without: the same contacts, in every lane.
    fn remembered_lookups_are_fresh_ones<L: Lane>() {
        let mut s = 5u64;
        let size = 4.0;
        let tiles = field(&mut s, 3, 150, size, 0.02, 0.3);
        let rocks = Rocks::new(size, 8, tiles);
        let tile: [usize; MAX_LANES] = std::array::from_fn(|i| i % 3);
        let (mut u, mut v, mut h, mut rho, mut k) = (L::ZERO, L::ZERO, L::ZERO, L::ZERO, L::ZERO);
        for i in 0..L::LANES {
            u.set_lane(i, next(&mut s) * 8.0 - 2.0);
            v.set_lane(i, next(&mut s) * 8.0 - 2.0);
            h.set_lane(i, next(&mut s) * 0.3);
            rho.set_lane(i, 0.05 + 0.1 * next(&mut s));
            k.set_lane(i, next(&mut s));
        }
        let mut clear = RockClearance::<L>::new();
        let (mut contacts, mut read) = (0, 0);
        for step in 0..20_000 {
            for i in 0..L::LANES {
                // Steps of up to 2 mm, and a jump of up to 0.3 m one step in 500.
                let scale = if step % 500 == 499 { 0.3 } else { 0.002 };
                let mut walk = |x: &mut L, lo: f64, hi: f64| {
                    let y = (x.lane(i) + scale * (2.0 * next(&mut s) - 1.0)).clamp(lo, hi);
                    x.set_lane(i, y);
                };
                walk(&mut u, -2.0, 6.0);
                walk(&mut v, -2.0, 6.0);
                walk(&mut h, -0.05, 0.35);
            }
            let before = clear.free_m;
            let (p, nu, nv, nn) = contact_lanes(&rocks, &tile, u, v, h, rho, k, &mut clear);
            for (i, &tile) in tile.iter().enumerate().take(L::LANES) {
                let fresh = rocks.contact(
                    tile,
                    u.lane(i),
                    v.lane(i),
                    h.lane(i),
                    rho.lane(i),
                    k.lane(i),
                );
                // As a lane holds it (f32 lanes round it).
                let held = |x: f64| {
                    let mut l = L::ZERO;
                    l.set_lane(0, x);
                    l.lane(0)
                };
                let fresh = (held(fresh.0), held(fresh.1), held(fresh.2), held(fresh.3));
                let got = (p.lane(i), nu.lane(i), nv.lane(i), nn.lane(i));
                assert_eq!(got, fresh, "lane {i}, step {step}");
                contacts += usize::from(fresh.0 >= 0.0);
                read += usize::from(clear.free_m.lane(i) != before.lane(i));
            }
        }
        // Both kinds of step occur: contacts, and most steps spared the lookup.
        let steps = 20_000 * L::LANES;
        assert!(
            contacts > steps / 20 && read < steps / 2,
            "{contacts} {read} of {steps}"
        );
    }

    #[test]
    fn remembered_lookups_are_fresh_ones_in_f64_and_f32() {
        remembered_lookups_are_fresh_ones::<wide::f64x8>();
        remembered_lookups_are_fresh_ones::<wide::f32x16>();
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
            &mut RockClearance::new(),
        );
        assert!((p.lane(0) - 0.2).abs() < 1e-15 && (p.lane(1) - 0.1).abs() < 1e-15);
        assert!((p.lane(7) - 0.2).abs() < 1e-15 && nn.lane(1) == 1.0);
    }
}
