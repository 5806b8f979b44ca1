//! The envelope's plane: its axes and bins, the cells of a panel and their counts, each
//! row's boundary, and the facing of a sample (a leg or a side downhill).

use crate::reference::Outcome;
use crate::stats::Allowable;
use std::path::PathBuf;

/// Which way the lander faces the slope: the downhill direction relative to the lander
/// (`downhill_azimuth_deg - yaw_deg`) within half a leg sector (`180 / legs` deg wide) of
/// a leg's azimuth, or between two legs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Facing {
    /// All samples (no `--azimuth`).
    All,
    /// A leg downhill.
    LegDownhill,
    /// A side (between two legs) downhill.
    SideDownhill,
}

impl Facing {
    /// Its name in the table and the picture.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Facing::All => "all",
            Facing::LegDownhill => "leg-downhill",
            Facing::SideDownhill => "side-downhill",
        }
    }

    /// The facing of a relative downhill azimuth (deg), given the legs' azimuths in B and
    /// the half width of a leg's sector (deg).
    pub(super) fn of(relative_deg: f64, (legs, half_deg): &(Vec<f64>, f64)) -> Facing {
        let near = legs.iter().any(|leg| {
            let d = (relative_deg - leg).rem_euclid(360.0);
            d.min(360.0 - d) <= *half_deg
        });
        if near {
            Facing::LegDownhill
        } else {
            Facing::SideDownhill
        }
    }
}

/// One axis of the plane: its column, unit and equal bins from `lo` to `hi`.
#[derive(Debug, Clone)]
pub struct Axis {
    /// The column.
    pub name: String,
    /// Its unit (the field's metadata; empty where it has none).
    pub unit: String,
    /// The low end of the first bin.
    pub lo: f64,
    /// The high end of the last bin.
    pub hi: f64,
    /// The number of bins.
    pub bins: usize,
}

impl Axis {
    /// The `k`-th edge of the bins (0: `lo`, `bins`: `hi`).
    #[must_use]
    pub fn edge(&self, k: usize) -> f64 {
        if k == self.bins {
            return self.hi;
        }
        self.lo + (self.hi - self.lo) * k as f64 / self.bins as f64
    }

    /// The bin `k` of `v`: `edge(k) <= v < edge(k + 1)`, the last bin closed (the data's
    /// largest value is its high end).
    pub(super) fn bin_of(&self, v: f64) -> usize {
        let guess = ((v - self.lo) / (self.hi - self.lo) * self.bins as f64).floor();
        let mut k = (guess.max(0.0) as usize).min(self.bins - 1);
        // The guess may be one off where `v` is within rounding of an edge.
        while k + 1 < self.bins && v >= self.edge(k + 1) {
            k += 1;
        }
        while k > 0 && v < self.edge(k) {
            k -= 1;
        }
        k
    }

    /// The axis's label: the column and its unit.
    #[must_use]
    pub fn label(&self) -> String {
        if self.unit.is_empty() || self.unit == "1" {
            self.name.clone()
        } else {
            format!("{} ({})", self.name, self.unit)
        }
    }

    /// The axis of `values` (finite) over their range; a constant column is widened around
    /// its value.
    pub(super) fn over(name: &str, unit: String, values: &[f64], bins: usize) -> Axis {
        let (lo, hi) = values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(*v), hi.max(*v))
            });
        let (lo, hi) = if lo > hi {
            (0.0, 1.0)
        } else if hi - lo <= 1e-12 * hi.abs().max(1.0) {
            let d = if lo == 0.0 { 0.5 } else { 0.05 * lo.abs() };
            (lo - d, hi + d)
        } else {
            (lo, hi)
        };
        Axis {
            name: name.to_string(),
            unit,
            lo,
            hi,
            bins,
        }
    }
}

/// A cell of the plane: its samples per outcome, and how many broke a limit.
#[derive(Debug, Clone, Default)]
pub struct Cell {
    /// Samples per outcome, in the order of `Outcome::ALL`.
    pub counts: [u64; Outcome::ALL.len()],
    /// Samples that broke a limit (`limits_broken` not empty).
    pub limits_broken: u64,
}

impl Cell {
    /// Its samples.
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// Its stable samples.
    #[must_use]
    pub fn stable(&self) -> u64 {
        self.counts[Outcome::Stable as usize]
    }
}

/// A row of cells (a bin of y) of a panel: its samples and the 99 %-stable boundary along
/// x of all of them.
#[derive(Debug, Clone)]
pub struct Row {
    /// Samples in the row.
    pub samples: u64,
    /// Stable samples in the row.
    pub stable: u64,
    /// The largest x with at least 99 % of the row's samples at or below it stable, with
    /// its 95 % interval (`stats::allowable_slope`'s rule along x).
    pub boundary: Allowable,
}

/// One panel: a slope band (and facing), its cells and rows.
#[derive(Debug, Clone)]
pub struct Panel {
    /// The slope band, deg: `[lo, hi)` (the last band `[lo, hi]`).
    pub slope_deg: (f64, f64),
    /// The facing of its samples.
    pub facing: Facing,
    /// Its cells, row by row (y bin 0 first), `x.bins` a row.
    pub cells: Vec<Cell>,
    /// Its rows, y bin 0 first.
    pub rows: Vec<Row>,
}

impl Panel {
    /// Its samples.
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.rows.iter().map(|r| r.samples).sum()
    }

    /// Its samples that broke a limit.
    #[must_use]
    pub fn limits_broken(&self) -> u64 {
        self.cells.iter().map(|c| c.limits_broken).sum()
    }

    /// The cell of x bin `i`, y bin `j`.
    #[must_use]
    pub fn cell(&self, i: usize, j: usize, nx: usize) -> &Cell {
        &self.cells[j * nx + i]
    }
}

/// The touchdown envelope of a sweep file.
#[derive(Debug, Clone)]
pub struct Envelope {
    /// The sweep file.
    pub path: PathBuf,
    /// The x axis.
    pub x: Axis,
    /// The y axis.
    pub y: Axis,
    /// The panels: slope bands in increasing order, each band's facings together.
    pub panels: Vec<Panel>,
    /// Rows of the file.
    pub rows: u64,
    /// Samples that never touched the surface (null touchdown state), left out.
    pub never_touched: u64,
    /// Samples left out for want of a value of x or y (null, NaN or infinite).
    pub no_value: u64,
    /// Samples left out with a slope outside the bands.
    pub outside_bands: u64,
    /// Whether the file has a `limits_broken` column.
    pub limits: bool,
    /// The sweep's seed, from its metadata.
    pub seed: String,
    /// What to say of the file where it holds fewer samples than it asked for: an
    /// interrupted sweep's (`output::sweep::interrupted_note`).
    pub interrupted: Option<String>,
}

impl Envelope {
    /// The samples in the panels.
    #[must_use]
    pub fn samples(&self) -> u64 {
        self.panels.iter().map(Panel::samples).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facing_is_within_half_a_leg_sector_of_a_leg() {
        let legs = (vec![45.0, 135.0, 225.0, 315.0], 22.5);
        assert_eq!(Facing::of(45.0, &legs), Facing::LegDownhill);
        assert_eq!(Facing::of(67.5, &legs), Facing::LegDownhill);
        assert_eq!(Facing::of(0.0, &legs), Facing::SideDownhill);
        assert_eq!(Facing::of(330.0, &legs), Facing::LegDownhill);
        assert_eq!(Facing::of(359.0, &legs), Facing::SideDownhill);
    }
}
