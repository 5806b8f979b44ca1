//! Pictures of a sweep file: the stability map, the tipped share per slope bin, and the
//! distributions of peak CG acceleration and damper stroke.

use super::canvas::{Area, Chart2d, FONT, OUTCOME_COLOURS, drawing, legend, save_png, span};
use crate::output::columns::Table;
use crate::reference::Outcome;
use crate::scenario::Scenario;
use crate::stability::static_limit_deg;
use crate::stats::{
    SECTOR_DEG, SECTORS, allowable_slope, quantile, relative_azimuth_deg, sector_of,
    wilson_interval,
};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// The sweep's columns the pictures use.
struct Sweep {
    /// Downhill azimuth relative to the lander, `downhill_azimuth_deg - yaw_deg` in
    /// [0, 360), deg.
    relative_azimuth: Vec<f64>,
    slope: Vec<f64>,
    /// Index into `Outcome::ALL`.
    outcome: Vec<u8>,
    peak_acceleration: Vec<f64>,
    /// The longest final damper stroke of the sample's legs, mm.
    stroke_mm: Vec<f64>,
    /// Footpads in B, from the scenario in the file (none if it does not read).
    tips_m: Option<Vec<[f64; 3]>>,
    /// Whether the scenario in the file has its dampers on.
    dampers: bool,
    /// The limits of the scenario in the file on the exceedance picture's axes.
    limit_marks: Vec<crate::exceedance::LimitMark>,
    /// "N samples, seed S", for the captions.
    about: String,
}

impl Sweep {
    fn read(path: &Path) -> anyhow::Result<Sweep> {
        let t = Table::read(path, |n| {
            matches!(
                n,
                "slope_deg" | "downhill_azimuth_deg" | "yaw_deg" | "peak_acceleration_m_s2"
            ) || n.ends_with("_stroke_m")
        })?;
        if t.rows == 0 {
            anyhow::bail!("{} holds no samples", path.display());
        }
        let (azimuth, yaw) = (
            t.column("downhill_azimuth_deg", path)?,
            t.column("yaw_deg", path)?,
        );
        let legs = t.legs("stroke_m");
        let strokes: Vec<&[f64]> = (0..legs)
            .map(|k| t.column(&format!("leg{k}_stroke_m"), path))
            .collect::<anyhow::Result<_>>()?;
        let scenario = t
            .meta
            .get("touchdown.scenario")
            .and_then(|s| Scenario::from_toml(s).ok());
        let tips_m = scenario.as_ref().map(|s| s.lander.tips_m());
        let dampers = scenario.as_ref().is_some_and(|s| s.damper.enabled);
        let limit_marks = scenario
            .as_ref()
            .map_or_else(Vec::new, crate::exceedance::limit_marks);
        Ok(Sweep {
            relative_azimuth: azimuth
                .iter()
                .zip(yaw)
                .map(|(a, y)| relative_azimuth_deg(*a, *y))
                .collect(),
            slope: t.column("slope_deg", path)?.to_vec(),
            outcome: t.outcome.clone(),
            peak_acceleration: t.column("peak_acceleration_m_s2", path)?.to_vec(),
            stroke_mm: (0..t.rows)
                .map(|i| 1e3 * strokes.iter().map(|s| s[i]).fold(0.0, f64::max))
                .collect(),
            tips_m,
            dampers,
            limit_marks,
            about: format!(
                "{}, seed {}",
                // A file short of its samples: an interrupted sweep's.
                match crate::output::sweep::samples_asked(|k| t.meta.get(k)) {
                    Some(asked) if (t.rows as u64) < asked =>
                        format!("{} of {asked} samples (an interrupted sweep)", t.rows),
                    _ => format!("{} samples", t.rows),
                },
                t.meta.get("touchdown.seed").map_or("?", String::as_str)
            ),
        })
    }

    /// The static limit at each relative azimuth 0, 0.5, ... 360 deg.
    fn limit_curve(&self) -> Vec<(f64, f64)> {
        let Some(tips) = &self.tips_m else {
            return Vec::new();
        };
        (0..=720)
            .filter_map(|i| {
                let phi = 0.5 * f64::from(i);
                static_limit_deg(tips, phi).map(|s| (phi, s))
            })
            .collect()
    }
}

/// The pictures of a sweep, by the end of their names.
pub(super) const PICTURES: [&str; 4] = ["stability-map", "tipped-by-slope", "loads", "exceedance"];

/// Writes the sweep's pictures, named by `name`; returns their paths.
pub(super) fn plot(path: &Path, name: &dyn Fn(&str) -> PathBuf) -> anyhow::Result<Vec<PathBuf>> {
    let s = Sweep::read(path)?;
    let limit = s.limit_curve();
    let mut written = Vec::new();
    let [map, tipped, loads, exceedance] = PICTURES.map(name);

    save_png(&map, (1000, 680), |root| stability_map(root, &s, &limit))?;
    written.push(map);

    save_png(&tipped, (1000, 620), |root| {
        tipped_by_slope(root, &s, &limit)
    })?;
    written.push(tipped);

    save_png(&loads, (1200, 520), |root| {
        let panels = root.split_evenly((1, 2));
        histogram(
            &panels[0],
            &format!("peak CG acceleration ({})", s.about),
            "peak CG acceleration (m/s²)",
            &s.peak_acceleration,
        )?;
        histogram(
            &panels[1],
            "damper stroke, longest leg of each sample",
            "final damper stroke (mm)",
            &s.stroke_mm,
        )
    })?;
    written.push(loads);

    let source = crate::output::sweep::SweepSource::Path(path.to_path_buf());
    let quantities = crate::exceedance::gather(&source, s.dampers)?;
    let rows = quantities.len().div_ceil(2) as u32;
    save_png(&exceedance, (1200, 40 + 460 * rows), |root| {
        super::exceedance::exceedance(root, &quantities, &s.limit_marks, &s.about)
    })?;
    written.push(exceedance);
    Ok(written)
}

/// Slope against relative downhill azimuth, a dot per sample coloured by its outcome (the
/// rarest outcomes drawn last, so that they show on a dense map), with the static limit and
/// the allowable slope of each azimuth sector over it.
fn stability_map(root: &Area<'_>, s: &Sweep, limit: &[(f64, f64)]) -> anyhow::Result<()> {
    let top = s
        .slope
        .iter()
        .chain(limit.iter().map(|p| &p.1))
        .fold(0.0f64, |m, v| m.max(*v));
    // Headroom above the data and the limit curve, so that the legend covers neither.
    let y_max = (top * 1.3 / 5.0).ceil().max(1.0) * 5.0;
    let mut chart = ChartBuilder::on(root)
        .caption(format!("Stability map: {}", s.about), (FONT, 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..360.0, 0.0..y_max)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc("downhill azimuth relative to the lander, from X_B (deg)")
        .y_desc("slope (deg)")
        .x_labels(9)
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    outcome_dots(&mut chart, s)?;
    allowable_per_sector(&mut chart, s)?;
    if !limit.is_empty() {
        chart
            .draw_series(LineSeries::new(
                limit.iter().copied(),
                BLACK.stroke_width(3),
            ))
            .map_err(drawing)?
            .label("static tipping limit atan(r/h)")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(3)));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// A dot per sample in the colour of its outcome, the commonest outcome first, and a
/// legend entry per outcome present with its count.
fn outcome_dots(chart: &mut Chart2d<'_, '_>, s: &Sweep) -> anyhow::Result<()> {
    // Bigger dots for fewer samples; single pixels when they would cover the map anyway.
    let radius = match s.slope.len() {
        0..=2_000 => 3,
        2_001..=20_000 => 2,
        20_001..=300_000 => 1,
        _ => 0,
    };
    // The commonest outcome first, the rarest last: on a dense map the few stable dots
    // among many tipped ones stay visible. Within an outcome, in sample order.
    let mut counts = [0usize; Outcome::ALL.len()];
    s.outcome.iter().for_each(|o| counts[usize::from(*o)] += 1);
    let mut order: Vec<usize> = (0..counts.len()).collect();
    order.sort_by_key(|k| std::cmp::Reverse(counts[*k]));
    for k in order {
        let c = OUTCOME_COLOURS[k];
        let dots = s
            .relative_azimuth
            .iter()
            .zip(&s.slope)
            .zip(&s.outcome)
            .filter(|(_, o)| usize::from(**o) == k)
            .map(|((a, sl), _)| (*a, *sl));
        if radius == 0 {
            chart
                .draw_series(dots.map(|p| Pixel::new(p, c)))
                .map_err(drawing)?;
        } else {
            chart
                .draw_series(dots.map(|p| Circle::new(p, radius, c.filled())))
                .map_err(drawing)?;
        }
    }
    // The legend: one entry per outcome present, with its count.
    for (k, outcome) in Outcome::ALL.iter().enumerate() {
        let n = s.outcome.iter().filter(|o| usize::from(**o) == k).count();
        if n == 0 {
            continue;
        }
        let c = OUTCOME_COLOURS[k];
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(drawing)?
            .label(format!("{} ({n})", outcome.name()))
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, c.filled()));
    }
    Ok(())
}

/// The allowable slope of each azimuth sector (as `touchdown report` finds it), dashed.
fn allowable_per_sector(chart: &mut Chart2d<'_, '_>, s: &Sweep) -> anyhow::Result<()> {
    // The allowable slope of each sector, as `touchdown report` finds it.
    let purple = RGBColor(110, 0, 150);
    let mut per_sector: Vec<Vec<(f64, bool)>> = vec![Vec::new(); SECTORS];
    for ((a, sl), o) in s.relative_azimuth.iter().zip(&s.slope).zip(&s.outcome) {
        per_sector[sector_of(*a)].push((*sl, Outcome::ALL[usize::from(*o)] == Outcome::Stable));
    }
    let mut any = false;
    for (k, samples) in per_sector.iter_mut().enumerate() {
        if let Some(allowable) = allowable_slope(samples).slope_deg() {
            let x0 = k as f64 * SECTOR_DEG;
            chart
                .draw_series(DashedLineSeries::new(
                    [(x0, allowable), (x0 + SECTOR_DEG, allowable)],
                    10,
                    5,
                    purple.stroke_width(4),
                ))
                .map_err(drawing)?;
            any = true;
        }
    }
    if any {
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
            .map_err(drawing)?
            .label("allowable slope per sector (>= 99 % stable)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], purple.stroke_width(4))
            });
    }
    Ok(())
}

/// A round bin width near `span / 18`: 1, 2, 2.5 or 5 times a power of ten.
fn bin_width(span: f64) -> f64 {
    let raw = (span / 18.0).max(1e-6);
    let decade = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|w| *w >= raw)
        .unwrap_or(10.0 * decade)
}

/// The share of each outcome per slope bin, with 95 % Wilson intervals, and the range of
/// the static limit over azimuth.
fn tipped_by_slope(root: &Area<'_>, s: &Sweep, limit: &[(f64, f64)]) -> anyhow::Result<()> {
    let range = span(s.slope.iter().copied(), 0.0);
    let width = bin_width(range.end - range.start);
    let first = (range.start / width).floor() * width;
    let bins = (((range.end - first) / width).floor() as usize + 1).max(1);
    let mut n = vec![0u64; bins];
    // Samples per outcome and bin.
    let mut by_outcome = vec![vec![0u64; bins]; Outcome::ALL.len()];
    for (sl, o) in s.slope.iter().zip(&s.outcome) {
        let b = (((sl - first) / width).floor().max(0.0) as usize).min(bins - 1);
        n[b] += 1;
        by_outcome[usize::from(*o)][b] += 1;
    }
    let (lim_lo, lim_hi) = limit.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
        (lo.min(p.1), hi.max(p.1))
    });
    let x_end =
        (first + bins as f64 * width).max(if limit.is_empty() { 0.0 } else { lim_hi + 1.0 });
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Outcome shares per {width} deg slope bin: {}", s.about),
            (FONT, 20),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(first..x_end, 0.0..1.0)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc("slope (deg)")
        .y_desc("share of the samples in the bin (95 % interval)")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    // Every outcome that occurs, so that the shares of a bin add up to 1 (where the samples
    // neither tipped nor stood went: sliding, mostly).
    let present: Vec<usize> = (0..Outcome::ALL.len())
        .filter(|k| by_outcome[*k].iter().any(|c| *c > 0))
        .collect();
    for (i, k) in present.iter().enumerate() {
        let (counts, colour, label) = (
            &by_outcome[*k],
            OUTCOME_COLOURS[*k],
            Outcome::ALL[*k].name(),
        );
        // Error bars side by side within the bin.
        let shift = 0.16 * (i as f64 - 0.5 * (present.len() as f64 - 1.0));
        let points: Vec<(f64, f64, f64, f64)> = (0..bins)
            .filter(|b| n[*b] > 0)
            .map(|b| {
                let (lo, hi) = wilson_interval(counts[b], n[b]);
                let x = first + (b as f64 + 0.5 + shift) * width;
                (x, lo, counts[b] as f64 / n[b] as f64, hi)
            })
            .collect();
        chart
            .draw_series(points.iter().map(|(x, lo, p, hi)| {
                ErrorBar::new_vertical(*x, *lo, *p, *hi, colour.stroke_width(2), 8)
            }))
            .map_err(drawing)?;
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|(x, _, p, _)| (*x, *p)),
                colour.stroke_width(2),
            ))
            .map_err(drawing)?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
    }
    if !limit.is_empty() {
        // The least and the largest static limit over azimuth (side and leg downhill, on
        // a regular gear).
        let grey = RGBColor(90, 90, 90);
        for x in [lim_lo, lim_hi] {
            chart
                .draw_series(DashedLineSeries::new(
                    [(x, 0.0), (x, 1.0)],
                    8,
                    5,
                    grey.stroke_width(2),
                ))
                .map_err(drawing)?;
        }
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
            .map_err(drawing)?
            .label(format!(
                "static tipping limit over azimuth: {lim_lo:.1} to {lim_hi:.1} deg"
            ))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], grey.stroke_width(2))
            });
    }
    legend(&mut chart, SeriesLabelPosition::MiddleLeft)
}

/// A histogram of `values` in 40 bins from 0; past 3 times the 99.9th percentile the
/// tail is counted in the caption instead, so that a few outliers do not flatten it.
fn histogram(area: &Area<'_>, caption: &str, x_desc: &str, values: &[f64]) -> anyhow::Result<()> {
    let mut finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let p999 = quantile(&mut finite, 0.999);
    // `quantile` sorted them.
    let max = finite.last().copied().unwrap_or(0.0).max(0.0);
    let top = if max > 3.0 * p999 && p999 > 0.0 {
        p999
    } else {
        max
    };
    let mut builder = ChartBuilder::on(area);
    let chart = builder
        .caption(caption, (FONT, 17))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70);
    if top <= 0.0 {
        // Nothing to bin (a sweep without dampers strokes nothing).
        let mut c = chart
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)
            .map_err(drawing)?;
        c.configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc("samples")
            .label_style((FONT, 13))
            .axis_desc_style((FONT, 15))
            .draw()
            .map_err(drawing)?;
        c.draw_series(std::iter::once(Text::new(
            format!("all {} samples at 0", values.len()),
            (0.3, 0.5),
            (FONT, 18),
        )))
        .map_err(drawing)?;
        return Ok(());
    }
    let bins = 40usize;
    let width = top / bins as f64;
    let mut counts = vec![0u64; bins];
    let mut beyond = 0u64;
    for v in &finite {
        let b = (v / width).floor() as usize;
        if b < bins {
            counts[b] += 1;
        } else if *v <= top {
            counts[bins - 1] += 1;
        } else {
            beyond += 1;
        }
    }
    let highest = counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    let x_desc = if beyond > 0 {
        format!("{x_desc}; {beyond} samples beyond, up to {max:.3}")
    } else {
        x_desc.to_string()
    };
    let mut c = chart
        .build_cartesian_2d(0.0..top, 0.0..highest * 1.08)
        .map_err(drawing)?;
    c.configure_mesh()
        .x_desc(x_desc)
        .y_desc("samples")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    let colour = RGBColor(31, 119, 180);
    c.draw_series(counts.iter().enumerate().map(|(b, n)| {
        let x0 = b as f64 * width;
        Rectangle::new(
            [(x0, 0.0), (x0 + width, *n as f64)],
            colour.mix(0.8).filled(),
        )
    }))
    .map_err(drawing)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bin_widths_are_round() {
        assert_eq!(bin_width(45.0), 2.5);
        assert_eq!(bin_width(60.0), 5.0);
        assert_eq!(bin_width(18.0), 1.0);
        assert_eq!(bin_width(9.0), 0.5);
    }
}
