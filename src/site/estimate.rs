//! Each facet's outcome shares from one sweep over the slopes and gravities of the body: the
//! samples whose slope lies within `slope_deg` of the facet's and whose gravity lies within
//! the fraction `gravity_fraction` of the facet's (a window centred on the facet's own
//! slope and gravity), counted; their shares with Wilson's 95 % intervals.
//!
//! The sweep draws slope uniformly and gravity uniformly or uniformly in its logarithm
//! (`GravityDraw`), so a window's samples are drawn over it with a density flat in slope and
//! flat, or proportional to `1/g`, in gravity, and its share is P averaged over it with that
//! density: for a P smooth in the window, off the facet's own by
//! `P_ss h_s^2 / 6 + P_gg (g h_g)^2 / 6` (the second derivatives; the first cancel in a
//! centred window where the density is flat), plus `-P_g g h_g^2 / 3` under the logarithmic
//! draw (the window's mean gravity is `g (1 - h_g^2 / 3)` to second order), and the
//! first-order term `P_s h_s / 2` only where the window is cut, at slope 0 or at the top of
//! the slopes drawn (docs/MODEL.md, "Landing sites").
//!
//! Counting is done once on a fine grid of the (slope, gravity) plane, with a summed-area
//! table per outcome, so a facet's window costs a constant time whatever the samples:
//! the window's edges are rounded to the grid, `GRID_PER_WINDOW` cells to a half-width.

use super::{FacetShare, SHARE_OUTCOMES};
use crate::reference::Outcome;
use crate::stats::wilson_interval;

/// Grid cells to a window's half-width (in slope, and in gravity at the smallest gravity):
/// the window's edges fall within half a cell, 1/16 of the half-width, of where they should.
pub const GRID_PER_WINDOW: f64 = 8.0;

/// The window a facet's shares count samples in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Half-width in slope, deg.
    pub slope_deg: f64,
    /// Half-width in gravity, as a fraction of the facet's gravity.
    pub gravity_fraction: f64,
}

impl Default for Window {
    fn default() -> Self {
        Window {
            slope_deg: 1.0,
            gravity_fraction: 0.05,
        }
    }
}

/// How the sweep draws gravity over its range (`--gravity-draw`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GravityDraw {
    /// Uniformly: a facet's window (a fraction of its gravity wide) holds a share of the
    /// samples that grows with its gravity, least at the smallest.
    #[default]
    Uniform,
    /// Uniformly in the logarithm: every facet's window the same share in gravity.
    LogUniform,
}

/// The sweep's samples counted on the grid: per outcome of `SHARE_OUTCOMES` and in all, a
/// summed-area table.
pub struct Counts {
    slope_max_deg: f64,
    gravity_min: f64,
    gravity_max: f64,
    slope_cell: f64,
    gravity_cell: f64,
    columns: usize,
    rows: usize,
    /// `(rows + 1) x (columns + 1)` sums per table: the samples in cells `[0, r) x [0, c)`;
    /// tables for the outcomes of `SHARE_OUTCOMES`, then all samples.
    tables: Vec<Vec<u64>>,
}

/// The grid's cells for these ranges and window, `(columns in slope, rows in gravity)`, as
/// `f64` (a window fine enough makes more than any machine holds), and the cells' sizes.
fn grid(
    slope_max_deg: f64,
    (gravity_min, gravity_max): (f64, f64),
    window: Window,
) -> ((f64, f64), (f64, f64)) {
    let slope_cell = window.slope_deg / GRID_PER_WINDOW;
    let gravity_cell = gravity_min * window.gravity_fraction / GRID_PER_WINDOW;
    let columns = (slope_max_deg / slope_cell).ceil().max(1.0);
    let rows = ((gravity_max - gravity_min) / gravity_cell).ceil().max(1.0);
    ((columns, rows), (slope_cell, gravity_cell))
}

/// Bytes the counts of a sweep over these ranges hold on the grid of `window` (one
/// summed-area table of 8-byte counts per outcome and one of all samples), whatever the
/// samples: a run refuses a window too fine for the machine before its sweep. `f64`: it
/// may exceed any machine's memory.
#[must_use]
pub fn grid_bytes(slope_max_deg: f64, gravities: (f64, f64), window: Window) -> f64 {
    let ((columns, rows), _) = grid(slope_max_deg, gravities, window);
    (columns + 1.0) * (rows + 1.0) * (SHARE_OUTCOMES.len() + 1) as f64 * 8.0
}

/// The window of a facet a lander could stand on that expects the fewest of the sweep's
/// samples (windows at slope 0, cut in half, and with gravity drawn uniformly, at the
/// smallest gravity, narrowest).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeastWindow {
    /// The facet's number.
    pub facet: u32,
    /// Its slope, deg, and gravity, m/s^2.
    pub slope_deg: f64,
    /// See `slope_deg`.
    pub gravity_m_s2: f64,
    /// The samples its window expects of the sweep's.
    pub expected: f64,
}

/// The samples a facet's window holds on average in a sweep of `samples` samples over these
/// ranges (slopes drawn uniformly on `[0, slope_max_deg]`, gravities on `gravities` as
/// `draw` says): the sweep's samples times the probability of its (slope, gravity)
/// rectangle, clipped to the ranges as the counts clip it.
#[must_use]
pub fn expected_samples(
    samples: u64,
    slope_max_deg: f64,
    (gravity_min, gravity_max): (f64, f64),
    draw: GravityDraw,
    window: Window,
    (slope_deg, gravity): (f64, f64),
) -> f64 {
    let covered = |lo: f64, hi: f64, min: f64, max: f64| (hi.min(max) - lo.max(min)).max(0.0);
    let s = covered(
        slope_deg - window.slope_deg,
        slope_deg + window.slope_deg,
        0.0,
        slope_max_deg,
    ) / slope_max_deg;
    let half = gravity * window.gravity_fraction;
    let (lo, hi) = (
        (gravity - half).max(gravity_min),
        (gravity + half).min(gravity_max),
    );
    let g = match draw {
        _ if hi <= lo => 0.0,
        GravityDraw::Uniform => (hi - lo) / (gravity_max - gravity_min),
        GravityDraw::LogUniform => (hi.ln() - lo.ln()) / (gravity_max.ln() - gravity_min.ln()),
    };
    samples as f64 * s * g
}

impl Counts {
    /// Counts `samples` (slope, deg; gravity, m/s^2; outcome) of a sweep that drew slopes on
    /// `[0, slope_max_deg]` and gravities on `[gravity_min, gravity_max]` (however drawn), on
    /// a grid for `window`, as they come (none is kept): it holds [`grid_bytes`] whatever
    /// their number. Samples outside the ranges are not counted.
    #[must_use]
    pub fn new(
        samples: impl Iterator<Item = (f64, f64, Outcome)>,
        slope_max_deg: f64,
        (gravity_min, gravity_max): (f64, f64),
        window: Window,
    ) -> Counts {
        let ((columns, rows), (slope_cell, gravity_cell)) =
            grid(slope_max_deg, (gravity_min, gravity_max), window);
        let (columns, rows) = (columns as usize, rows as usize);
        let w = columns + 1;
        // Each table counts cell (r, c) at [(r + 1) w + c + 1], then sums in place.
        let mut tables = vec![vec![0u64; (rows + 1) * w]; SHARE_OUTCOMES.len() + 1];
        for (slope, gravity, outcome) in samples {
            if !(0.0..=slope_max_deg).contains(&slope)
                || !(gravity_min..=gravity_max).contains(&gravity)
            {
                continue;
            }
            let c = ((slope / slope_cell) as usize).min(columns - 1);
            let r = (((gravity - gravity_min) / gravity_cell) as usize).min(rows - 1);
            let at = (r + 1) * w + c + 1;
            tables[SHARE_OUTCOMES.len()][at] += 1;
            if let Some(k) = SHARE_OUTCOMES.iter().position(|o| *o == outcome) {
                tables[k][at] += 1;
            }
        }
        for t in &mut tables {
            for r in 1..=rows {
                for c in 1..=columns {
                    t[r * w + c] += t[(r - 1) * w + c] + t[r * w + c - 1] - t[(r - 1) * w + c - 1];
                }
            }
        }
        Counts {
            slope_max_deg,
            gravity_min,
            gravity_max,
            slope_cell,
            gravity_cell,
            columns,
            rows,
            tables,
        }
    }

    /// The samples in cells `[c0, c1) x [r0, r1)` of table `k`.
    fn sum(&self, k: usize, (c0, c1): (usize, usize), (r0, r1): (usize, usize)) -> u64 {
        let t = &self.tables[k];
        let w = self.columns + 1;
        t[r1 * w + c1] + t[r0 * w + c0] - t[r0 * w + c1] - t[r1 * w + c0]
    }

    /// The samples in the window about `slope_deg` and `gravity`, and the shares of
    /// `SHARE_OUTCOMES` among them; `None` where the window holds no sample.
    #[must_use]
    pub fn shares(
        &self,
        slope_deg: f64,
        gravity: f64,
        window: Window,
    ) -> (u64, Option<[FacetShare; 4]>) {
        // Window edges rounded to the nearest grid line, clipped to the sweep's ranges.
        let line = |x: f64, cell: f64, n: usize| ((x / cell).round().max(0.0) as usize).min(n);
        let slope = (
            line(slope_deg - window.slope_deg, self.slope_cell, self.columns),
            line(slope_deg + window.slope_deg, self.slope_cell, self.columns),
        );
        let half = gravity * window.gravity_fraction;
        let g = (
            line(
                gravity - half - self.gravity_min,
                self.gravity_cell,
                self.rows,
            ),
            line(
                gravity + half - self.gravity_min,
                self.gravity_cell,
                self.rows,
            ),
        );
        let n = self.sum(SHARE_OUTCOMES.len(), slope, g);
        if n == 0 {
            return (0, None);
        }
        let shares = std::array::from_fn(|k| {
            let hits = self.sum(k, slope, g);
            let (low, high) = wilson_interval(hits, n);
            FacetShare {
                p: hits as f64 / n as f64,
                low,
                high,
            }
        });
        (n, Some(shares))
    }

    /// Whether a facet of this slope and gravity lies within the sweep's ranges.
    #[must_use]
    pub fn covers(&self, slope_deg: f64, gravity: f64) -> bool {
        (0.0..=self.slope_max_deg).contains(&slope_deg)
            && (self.gravity_min..=self.gravity_max).contains(&gravity)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Samples on a regular lattice of the plane, stable below `limit(gravity)`.
    fn lattice(limit: impl Fn(f64) -> f64) -> Vec<(f64, f64, Outcome)> {
        let mut v = Vec::new();
        for i in 0..3000 {
            for j in 0..200 {
                let s = 30.0 * (f64::from(i) + 0.5) / 3000.0;
                let g = 1.0 + (f64::from(j) + 0.5) / 200.0;
                let o = if s < limit(g) {
                    Outcome::Stable
                } else {
                    Outcome::Tipped
                };
                v.push((s, g, o));
            }
        }
        v
    }

    #[test]
    fn a_window_counts_the_samples_near_a_facet_and_no_others() {
        let window = Window::default();
        // Stable below 15 deg at any gravity: a window wholly below is all stable, one
        // wholly above none, and one centred on 15 deg half (the share of a step at its
        // centre), within the grid's rounding of the edges (1/16 of the half-width on
        // each side: 1/32 of the window, 0.031).
        let samples = lattice(|_| 15.0);
        let counts = Counts::new(samples.iter().copied(), 30.0, (1.0, 2.0), window);
        let (n, s) = counts.shares(10.0, 1.5, window);
        let s = s.unwrap();
        assert_eq!((s[0].p, s[1].p), (1.0, 0.0));
        // 2 deg of 30 and 10 % of 1.5 out of 1: 3000 * 2/30 * 200 * 0.15 = 6000 samples.
        assert!((n as f64 - 6000.0).abs() <= 0.07 * 6000.0, "{n}");
        let (_, s) = counts.shares(20.0, 1.2, window);
        assert_eq!(s.unwrap()[0].p, 0.0);
        let (_, s) = counts.shares(15.0, 1.7, window);
        let p = s.unwrap()[0].p;
        assert!((p - 0.5).abs() < 0.031, "{p}");
        // The Wilson interval of its count.
        let (n, s) = counts.shares(15.0, 1.7, window);
        let s = s.unwrap()[0];
        let (lo, hi) = wilson_interval((s.p * n as f64).round() as u64, n);
        assert!((s.low - lo).abs() < 1e-12 && (s.high - hi).abs() < 1e-12);
    }

    #[test]
    fn a_window_expects_its_share_of_the_samples_under_either_draw() {
        // Slopes on [0, 40] deg, gravities on [1, 8] (a factor of 8), windows of +-1 deg
        // and +-5 %, 1e6 samples.
        let w = Window {
            slope_deg: 1.0,
            gravity_fraction: 0.05,
        };
        let e = |draw, at| expected_samples(1_000_000, 40.0, (1.0, 8.0), draw, w, at);
        let log_width = (1.05_f64 / 0.95).ln() / 8.0_f64.ln();
        // Drawn uniformly: the window's area over the rectangle's, growing with the
        // gravity; in the logarithm, the same for every whole window.
        for g in [1.2, 2.0, 5.0, 7.5] {
            let uniform = 1e6 * (2.0 / 40.0) * (0.1 * g / 7.0);
            let log = 1e6 * (2.0 / 40.0) * log_width;
            assert!((e(GravityDraw::Uniform, (20.0, g)) / uniform - 1.0).abs() < 1e-12);
            assert!((e(GravityDraw::LogUniform, (20.0, g)) / log - 1.0).abs() < 1e-12);
        }
        // Clipped: at slope 0 half the window; at the ranges' ends in gravity only the part
        // inside ([1, 1.05] of the window about 1, [7.6, 8] about 8).
        let half = e(GravityDraw::LogUniform, (0.0, 4.0)) / e(GravityDraw::LogUniform, (20.0, 4.0));
        assert!((half - 0.5).abs() < 1e-12);
        let low = 1e6 * (2.0 / 40.0) * 1.05_f64.ln() / 8.0_f64.ln();
        assert!((e(GravityDraw::LogUniform, (20.0, 1.0)) / low - 1.0).abs() < 1e-12);
        let high = 1e6 * (2.0 / 40.0) * (8.0_f64 / 7.6).ln() / 8.0_f64.ln();
        assert!((e(GravityDraw::LogUniform, (20.0, 8.0)) / high - 1.0).abs() < 1e-12);
        let high_uniform = 1e6 * (2.0 / 40.0) * (0.4 / 7.0);
        assert!((e(GravityDraw::Uniform, (20.0, 8.0)) / high_uniform - 1.0).abs() < 1e-12);
        // Outside the ranges, nothing.
        assert_eq!(e(GravityDraw::LogUniform, (20.0, 20.0)), 0.0);
        assert_eq!(e(GravityDraw::Uniform, (20.0, 20.0)), 0.0);
        // The least-served whole window of the uniform draw, at the smallest gravity whose
        // window is whole (1 / 0.95): 0.31 of what the logarithmic draw gives it (and
        // every other window), its width 0.1 / 0.95 over 7 against ln(1.05 / 0.95) / ln 8.
        let least_uniform = e(GravityDraw::Uniform, (20.0, 1.0 / 0.95));
        let least_log = e(GravityDraw::LogUniform, (20.0, 1.0 / 0.95));
        let ratio = least_uniform / least_log;
        let expected = (0.1 / 0.95 / 7.0) / log_width;
        assert!(
            (ratio / expected - 1.0).abs() < 1e-12,
            "{ratio} against {expected}"
        );
        assert!(ratio < 0.35, "{ratio}");
    }

    #[test]
    fn the_gravity_window_follows_the_facets_gravity() {
        // Stable below a limit that rises with gravity (10 deg at g = 1, 20 at g = 2): a
        // window at g centred on that limit is half stable (the gravity window is narrow:
        // the limit moves by 10 g * 0.05 = 0.75 deg over it at g = 1.5, symmetric about the
        // centre, so the share stays 0.5 within the grid's rounding).
        let samples = lattice(|g| 10.0 * g);
        let window = Window::default();
        let counts = Counts::new(samples.iter().copied(), 30.0, (1.0, 2.0), window);
        for g in [1.2, 1.5, 1.8] {
            let (_, s) = counts.shares(10.0 * g, g, window);
            let p = s.unwrap()[0].p;
            assert!((p - 0.5).abs() < 0.035, "g {g}: {p}");
            // Away from the limit by more than the window: all one way.
            let (_, s) = counts.shares(10.0 * g - 2.0, g, window);
            assert_eq!(s.unwrap()[0].p, 1.0, "g {g}");
        }
        // Outside the sweep's ranges: no samples.
        let (n, s) = counts.shares(15.0, 3.0, window);
        assert_eq!((n, s), (0, None));
        assert!(!counts.covers(15.0, 3.0) && counts.covers(15.0, 1.5));
    }
}
