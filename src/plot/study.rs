//! The picture of `touchdown study`: the allowable slope of each azimuth sector against the
//! varied value, with its 95 % intervals, and the static tipping limit beside it.

use super::canvas::{Area, Chart2d, FONT, SERIES_COLOURS, drawing, legend, save_png, span};
use crate::stats::{Allowable, SECTOR_DEG, SECTORS};
use crate::study::{About, Row};
use plotters::prelude::*;
use std::path::Path;

/// Writes the chart of `rows` to `out` (PNG).
pub(crate) fn study_chart(out: &Path, rows: &[Row], about: &About<'_>) -> anyhow::Result<()> {
    save_png(out, (1100, 700), |root| draw(root, rows, about))
}

/// The chart of `rows` on `root`.
fn draw(root: &Area<'_>, rows: &[Row], about: &About<'_>) -> anyhow::Result<()> {
    let x = span(rows.iter().map(|r| r.value), 0.06);
    let least: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.value, r.static_range?.0)))
        .collect();
    let greatest: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.value, r.static_range?.1)))
        .collect();
    let top = rows
        .iter()
        .flat_map(|r| r.allowable.iter())
        .filter_map(|a| match a {
            Allowable::Slope { high_deg, .. } => Some(*high_deg),
            Allowable::NoSlope { below_deg } => Some(*below_deg),
            Allowable::TooFewSamples(_) => None,
        })
        .chain(greatest.iter().map(|p| p.1))
        .fold(1.0f64, f64::max);
    // Headroom for the legend.
    let y_max = (top * 1.35 / 5.0).ceil() * 5.0;
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!(
                "Allowable slope against {}: {}, {} samples per value, seed {}",
                about.key, about.scenario, about.samples, about.seed
            ),
            (FONT, 19),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(x, 0.0..y_max)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(about.key)
        .y_desc("allowable slope, deg (95 % interval)")
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    sectors(&mut chart, rows)?;
    limits(&mut chart, rows, &least, &greatest)?;
    legend(&mut chart, SeriesLabelPosition::UpperLeft)
}

/// The allowable slope of each sector against the value, with its 95 % interval as a
/// whisker (neighbouring sectors' whiskers side by side).
fn sectors(chart: &mut Chart2d<'_, '_>, rows: &[Row]) -> anyhow::Result<()> {
    let width = span(rows.iter().map(|r| r.value), 0.0);
    // Whiskers of neighbouring sectors side by side, a little apart.
    let step = 0.006 * (width.end - width.start);
    for k in 0..SECTORS {
        let colour = SERIES_COLOURS[k % SERIES_COLOURS.len()];
        let shift = step * (k as f64 - 0.5 * (SECTORS as f64 - 1.0));
        let points: Vec<(f64, f64, f64, f64)> = rows
            .iter()
            .filter_map(|r| match r.allowable[k] {
                Allowable::Slope {
                    slope_deg,
                    low_deg,
                    high_deg,
                } => Some((r.value + shift, low_deg, slope_deg, high_deg)),
                _ => None,
            })
            .collect();
        chart
            .draw_series(points.iter().map(|(x, lo, s, hi)| {
                ErrorBar::new_vertical(*x, *lo, *s, *hi, colour.stroke_width(2), 6)
            }))
            .map_err(drawing)?;
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|(x, _, s, _)| (*x, *s)),
                colour.stroke_width(2),
            ))
            .map_err(drawing)?
            .label(format!(
                "{:.0}–{:.0} deg",
                k as f64 * SECTOR_DEG,
                (k + 1) as f64 * SECTOR_DEG
            ))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
    }
    Ok(())
}

/// A cross at 0 where a sector has no allowable slope, and the static limit's least and
/// greatest over azimuth, dashed.
fn limits(
    chart: &mut Chart2d<'_, '_>,
    rows: &[Row],
    least: &[(f64, f64)],
    greatest: &[(f64, f64)],
) -> anyhow::Result<()> {
    // A sector without an allowable slope at a value: a cross at 0.
    let none: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| {
            r.allowable
                .iter()
                .any(|a| matches!(a, Allowable::NoSlope { .. }))
        })
        .map(|r| (r.value, 0.0))
        .collect();
    if !none.is_empty() {
        let black = RGBColor(0, 0, 0);
        chart
            .draw_series(
                none.iter()
                    .map(|p| Cross::new(*p, 7, black.stroke_width(2))),
            )
            .map_err(drawing)?
            .label("× at 0: a sector with no allowable slope")
            .legend(move |(x, y)| Cross::new((x + 9, y), 5, black.stroke_width(2)));
    }
    for (line, label, colour) in [
        (least, "static limit, least over azimuth", RGBColor(0, 0, 0)),
        (greatest, "static limit, greatest", RGBColor(120, 120, 120)),
    ] {
        if line.is_empty() {
            continue;
        }
        chart
            .draw_series(DashedLineSeries::new(
                line.iter().copied(),
                8,
                5,
                colour.stroke_width(2),
            ))
            .map_err(drawing)?
            .label(label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
    }
    Ok(())
}
