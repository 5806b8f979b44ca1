//! `touchdown envelope`: the touchdown envelope of a sweep, the outcome shares over the
//! plane of two of its columns (by default the speeds along and towards the surface at the
//! first contact), one panel per slope band (and, optionally, per facing: a leg or a side
//! of the lander downhill). Per cell of the plane the samples, the share of each outcome
//! and the stable share's 95 % interval; per row of cells the 99 %-stable boundary along
//! x, by the rule of `report`'s allowable slope (`stats::allowable_slope`), with its
//! interval. What `plot::envelope` draws and `commands::envelope` writes (MODEL.md section
//! 11).

mod plane;
mod read;
mod table;

use crate::reference::Outcome;
use crate::stats::allowable_slope;
use anyhow::{anyhow, bail};
use std::path::Path;

pub use plane::{Axis, Cell, Envelope, Facing, Panel, Row};
pub use table::{markdown, panel_title, write_csv};

/// The default x column: the speed along the surface at the first contact.
pub const DEFAULT_X: &str = "touchdown_tangential_speed_m_s";

/// The default y column: the speed towards the surface at the first contact.
pub const DEFAULT_Y: &str = "touchdown_normal_speed_m_s";

/// What to build the envelope of.
#[derive(Debug, Clone)]
pub struct Settings {
    /// The column along x.
    pub x: String,
    /// The column along y.
    pub y: String,
    /// Cells along x and along y (each at least 1).
    pub bins: (usize, usize),
    /// The edges of the slope bands, deg, increasing (default: from the sweep's slopes).
    pub slope_bands: Option<Vec<f64>>,
    /// One panel per facing (a leg or a side downhill) as well as per slope band.
    pub azimuth: bool,
}

/// Refuses an envelope without a sample to place: no sample touched the ground, or the
/// column along x or y has no value (null, NaN or infinite) in any that did, so the picture
/// would be empty.
fn refuse_empty(path: &Path, settings: &Settings, s: &read::Samples) -> anyhow::Result<()> {
    if !s.x.is_empty() {
        return Ok(());
    }
    let touched = s.rows - s.never_touched;
    if touched == 0 {
        bail!(
            "{}: none of its {} samples touched the ground: an envelope has nothing to place",
            path.display(),
            s.rows
        );
    }
    let (flag, column) = if s.with_value.0 == 0 {
        ("--x", &settings.x)
    } else if s.with_value.1 == 0 {
        ("--y", &settings.y)
    } else {
        bail!(
            "{}: no sample that touched the ground has values of both {} (--x) and {} (--y) \
             (each is null, NaN or infinite where the other is not): an envelope has nothing \
             to place",
            path.display(),
            settings.x,
            settings.y
        );
    };
    bail!(
        "{flag} {column}: the column has no value (null, NaN or infinite) in any of the {touched} \
         samples of {} that touched the ground: an envelope along it would be empty; choose \
         another column",
        path.display()
    )
}

/// An envelope asked for, checked against its sweep file before its samples are read.
pub struct Checked {
    path: std::path::PathBuf,
    settings: Settings,
    /// The units of x and y.
    units: (String, String),
    /// The legs' azimuths and half a leg's sector, with `--azimuth`.
    legs: Option<read::Legs>,
    /// The file's schema metadata.
    meta: arrow_schema::Metadata,
}

/// Checks `settings` against the sweep file at `path`: the bins and bands, the file a
/// sweep with numeric x and y columns, and with `--azimuth` a scenario whose legs read.
/// Every refusal but those of the data itself, made before the samples are read.
pub fn check(path: &Path, settings: &Settings) -> anyhow::Result<Checked> {
    let (nx, ny) = settings.bins;
    if nx == 0 || ny == 0 {
        bail!("--bins {nx},{ny}: at least one bin along each axis");
    }
    if let Some(bands) = &settings.slope_bands {
        check_bands(bands)?;
    }
    let (schema, _) = crate::output::read::open(path, crate::output::read::format_of(path)?)?;
    let units = read::check_columns(path, &schema, (settings.x.as_str(), settings.y.as_str()))?;
    let legs = if settings.azimuth {
        Some(legs_of(path, schema.metadata())?)
    } else {
        None
    };
    Ok(Checked {
        path: path.to_path_buf(),
        settings: settings.clone(),
        units,
        legs,
        meta: schema.metadata().clone(),
    })
}

impl Checked {
    /// The facings of each slope band: two with `--azimuth`, else one.
    #[must_use]
    pub fn facings(&self) -> usize {
        if self.settings.azimuth { 2 } else { 1 }
    }

    /// The panels, where `--slope-bands` gives the bands (the default bands are the
    /// data's, one to three, known once it is read).
    #[must_use]
    pub fn panels(&self) -> Option<usize> {
        let bands = self.settings.slope_bands.as_ref()?;
        Some((bands.len() - 1) * self.facings())
    }

    /// The samples the sweep file asked for: the most rows it holds.
    #[must_use]
    pub fn samples_asked(&self) -> Option<u64> {
        crate::output::sweep::samples_asked(|k| self.meta.get(k))
    }

    /// The envelope: the samples read, the slope bands made and the cells counted; `fits`
    /// is asked whether the panels (their count given) may be made before their cells are.
    pub fn build(self, fits: impl FnOnce(usize) -> anyhow::Result<()>) -> anyhow::Result<Envelope> {
        let asked = self.samples_asked();
        let (path, settings) = (self.path.as_path(), &self.settings);
        let (nx, ny) = settings.bins;
        let s = read::samples(path, (&settings.x, &settings.y), self.legs.as_ref())?;
        refuse_empty(path, settings, &s)?;
        let bands = match &settings.slope_bands {
            Some(b) => b.clone(),
            None => default_bands(&s.slope_deg),
        };
        let facings: &[Facing] = if settings.azimuth {
            &[Facing::LegDownhill, Facing::SideDownhill]
        } else {
            &[Facing::All]
        };
        fits((bands.len() - 1) * facings.len())?;
        let (x_unit, y_unit) = self.units;
        let x = Axis::over(&settings.x, x_unit, &s.x, nx);
        let y = Axis::over(&settings.y, y_unit, &s.y, ny);
        let mut panels: Vec<Panel> = bands
            .windows(2)
            .flat_map(|w| {
                facings.iter().map(|f| Panel {
                    slope_deg: (w[0], w[1]),
                    facing: *f,
                    cells: vec![Cell::default(); nx * ny],
                    rows: Vec::new(),
                })
            })
            .collect();
        // Each panel's rows: (x, stable) of their samples, for the boundary.
        let mut rows: Vec<Vec<Vec<(f64, bool)>>> = vec![vec![Vec::new(); ny]; panels.len()];
        let mut outside_bands = 0;
        for k in 0..s.x.len() {
            let Some(band) = band_of(&bands, s.slope_deg[k]) else {
                outside_bands += 1;
                continue;
            };
            let p =
                band * facings.len() + facings.iter().position(|f| *f == s.facing[k]).unwrap_or(0);
            let (i, j) = (x.bin_of(s.x[k]), y.bin_of(s.y[k]));
            let cell = &mut panels[p].cells[j * nx + i];
            cell.counts[usize::from(s.outcome[k])] += 1;
            cell.limits_broken += u64::from(s.broke[k]);
            rows[p][j].push((
                s.x[k],
                usize::from(s.outcome[k]) == Outcome::Stable as usize,
            ));
        }
        for (panel, rows) in panels.iter_mut().zip(rows) {
            panel.rows = rows
                .into_iter()
                .map(|mut r| Row {
                    samples: r.len() as u64,
                    stable: r.iter().filter(|v| v.1).count() as u64,
                    boundary: allowable_slope(&mut r),
                })
                .collect();
        }
        Ok(Envelope {
            interrupted: crate::output::sweep::interrupted_note(path, s.rows, asked),
            path: self.path,
            x,
            y,
            panels,
            rows: s.rows,
            never_touched: s.never_touched,
            no_value: s.no_value,
            outside_bands,
            limits: s.limits,
            seed: self
                .meta
                .get("touchdown.seed")
                .cloned()
                .unwrap_or_else(|| "?".to_string()),
        })
    }
}

/// Refuses slope bands that are not at least two increasing edges in [0, 90] deg.
fn check_bands(bands: &[f64]) -> anyhow::Result<()> {
    let given = bands
        .iter()
        .map(f64::to_string)
        .collect::<Vec<_>>()
        .join(",");
    if bands.len() < 2 {
        bail!("--slope-bands {given}: at least two edges (one band), e.g. 0,10,20,30");
    }
    if let Some(b) = bands.iter().find(|b| !(0.0..=90.0).contains(*b)) {
        bail!("--slope-bands {given}: {b} is not a slope from 0 to 90 deg");
    }
    if let Some(w) = bands.windows(2).find(|w| w[1] <= w[0]) {
        bail!(
            "--slope-bands {given}: the edges must increase ({} then {})",
            w[0],
            w[1]
        );
    }
    Ok(())
}

/// Slope bands over the sweep's slopes: one band for a fixed slope, else three equal bands
/// of a round width (1, 1.5, 2, 2.5, 3 or 5 times a power of ten) from a multiple of it.
fn default_bands(slopes: &[f64]) -> Vec<f64> {
    let (lo, hi) = slopes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    if lo > hi {
        return vec![0.0, 90.0];
    }
    if hi - lo < 1e-9 {
        return vec![lo, hi];
    }
    let raw = (hi - lo) / 3.0;
    let decade = 10f64.powf(raw.log10().floor());
    let width = [1.0, 1.5, 2.0, 2.5, 3.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|w| *w >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade);
    let first = (lo / width).floor() * width;
    let mut edges = vec![first];
    while *edges.last().unwrap_or(&hi) < hi {
        edges.push(first + width * edges.len() as f64);
    }
    if edges.len() < 2 {
        edges.push(first + width);
    }
    edges
}

/// The band of a slope: `[edge k, edge k+1)`, the last band closed; `None` outside.
fn band_of(bands: &[f64], slope: f64) -> Option<usize> {
    let last = bands.len() - 1;
    if !(slope >= bands[0] && slope <= bands[last]) {
        return None;
    }
    Some(
        bands
            .iter()
            .rposition(|e| *e <= slope)
            .unwrap_or(0)
            .min(last - 1),
    )
}

/// The legs' azimuths in B (deg) and half a leg's sector, from the scenario stored in the
/// file, for `--azimuth`.
fn legs_of(path: &Path, meta: &arrow_schema::Metadata) -> anyhow::Result<read::Legs> {
    let text = meta.get("touchdown.scenario").ok_or_else(|| {
        anyhow!(
            "--azimuth: {} has no scenario in its metadata (touchdown.scenario) to read the \
             legs' azimuths from",
            path.display()
        )
    })?;
    let scenario = crate::scenario::Scenario::from_toml(text).map_err(|e| {
        anyhow!(
            "--azimuth: the scenario stored in {} does not read, so its legs' azimuths are \
             unknown: {e}",
            path.display()
        )
    })?;
    let tips = scenario.lander.tips_m();
    let azimuths = tips
        .iter()
        .map(|t| t[1].atan2(t[0]).to_degrees().rem_euclid(360.0))
        .collect();
    Ok((azimuths, 90.0 / tips.len() as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_bands_are_three_round_ones() {
        assert_eq!(default_bands(&[0.0, 44.9]), vec![0.0, 15.0, 30.0, 45.0]);
        assert_eq!(default_bands(&[0.0, 45.0]), vec![0.0, 15.0, 30.0, 45.0]);
        assert_eq!(default_bands(&[20.0, 70.0]), vec![20.0, 40.0, 60.0, 80.0]);
        assert_eq!(default_bands(&[10.0, 10.0]), vec![10.0, 10.0]);
    }

    #[test]
    fn slopes_fall_into_half_open_bands() {
        let b = [0.0, 15.0, 30.0, 45.0];
        assert_eq!(band_of(&b, 0.0), Some(0));
        assert_eq!(band_of(&b, 15.0), Some(1));
        assert_eq!(band_of(&b, 45.0), Some(2));
        assert_eq!(band_of(&b, 45.1), None);
        assert_eq!(band_of(&[10.0, 10.0], 10.0), Some(0));
    }
}
