//! The picture of `touchdown sensitivity --png`: per output, the first-order and total
//! Sobol index of every varied input as bars, with their 95 % bootstrap intervals.

use super::canvas::{Area, FONT, drawing, save_png};
use crate::sensitivity::{Analysis, Indices, OUTPUTS};
use plotters::prelude::*;
use std::path::Path;

/// Colours of the first-order and the total indices.
const FIRST: RGBColor = RGBColor(31, 119, 180);
const TOTAL: RGBColor = RGBColor(255, 127, 14);

/// Writes the bar chart of `analysis` to `out` (PNG), titled `title`.
pub fn sensitivity_chart(out: &Path, analysis: &Analysis, title: &str) -> anyhow::Result<()> {
    let d = analysis.names.len();
    // Two bars of about 11 px per input in each panel, and room for captions and axes.
    let panel_height = 110 + 26 * d as u32;
    save_png(out, (1400, 60 + 2 * panel_height), |root| {
        let (top, body) = root.split_vertically(60);
        top.draw(&Text::new(title.to_string(), (14, 8), (FONT, 20)))
            .map_err(drawing)?;
        let key = |x: i32, colour: RGBColor, text: &str| -> anyhow::Result<()> {
            top.draw(&Rectangle::new([(x, 38), (x + 26, 50)], colour.filled()))
                .map_err(drawing)?;
            top.draw(&Text::new(text.to_string(), (x + 32, 36), (FONT, 16)))
                .map_err(drawing)
        };
        key(14, FIRST, "first-order S_i (alone)")?;
        key(250, TOTAL, "total ST_i (with interactions)")?;
        top.draw(&Text::new(
            "whiskers: 95 % bootstrap interval".to_string(),
            (540, 36),
            (FONT, 16),
        ))
        .map_err(drawing)?;
        let panels = body.split_evenly((2, 2));
        for ((panel, name), (mean, ix)) in panels.iter().zip(OUTPUTS).zip(&analysis.outputs) {
            draw_panel(panel, name, *mean, ix.as_ref(), &analysis.names)?;
        }
        Ok(())
    })
}

/// One output's bars: input `q` on row `d - 1 - q` (the first input on top).
fn draw_panel(
    area: &Area<'_>,
    name: &str,
    mean: f64,
    ix: Option<&Indices>,
    names: &[&str],
) -> anyhow::Result<()> {
    let d = names.len();
    let caption = format!("{name}: mean {mean:.4}");
    let Some(ix) = ix else {
        area.draw(&Text::new(caption, (20, 10), (FONT, 18)))
            .map_err(drawing)?;
        area.draw(&Text::new(
            "no variance: every sample gives the same value".to_string(),
            (20, 60),
            (FONT, 16),
        ))
        .map_err(drawing)?;
        return Ok(());
    };
    // From 0 (or the lowest interval end, as estimates can dip below 0) to 1 (or the
    // highest end).
    let ends = ix
        .first
        .iter()
        .chain(&ix.total)
        .flat_map(|i| [i.low, i.high]);
    let (lo, hi) = ends
        .filter(|x| x.is_finite())
        .fold((0.0f64, 1.0f64), |(a, b), x| (a.min(x), b.max(x)));
    let (lo, hi) = ((lo - 0.02).max(-0.5), (hi + 0.02).min(1.5));
    let rows = -0.6..(d as f64 - 0.4);
    let row_of = |y: f64| -> Option<usize> {
        let r = y.round();
        ((y - r).abs() < 1e-6 && r >= 0.0 && r < d as f64).then(|| d - 1 - r as usize)
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 18))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(190)
        .build_cartesian_2d(lo..hi, rows)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .y_labels(d + 1)
        .y_label_formatter(&|y| row_of(*y).map_or(String::new(), |q| names[q].to_string()))
        .x_desc("Sobol index")
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 15))
        .draw()
        .map_err(drawing)?;
    for q in 0..d {
        let y = (d - 1 - q) as f64;
        for (index, colour, (from, to)) in [
            (ix.first[q], FIRST, (y + 0.04, y + 0.36)),
            (ix.total[q], TOTAL, (y - 0.36, y - 0.04)),
        ] {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(0.0, from), (index.estimate.clamp(lo, hi), to)],
                    colour.filled(),
                )))
                .map_err(drawing)?;
            if index.low.is_finite() && index.high.is_finite() {
                let mid = 0.5 * (from + to);
                let (a, b) = (index.low.clamp(lo, hi), index.high.clamp(lo, hi));
                let whisker = [
                    vec![(a, mid), (b, mid)],
                    vec![(a, from + 0.06), (a, to - 0.06)],
                    vec![(b, from + 0.06), (b, to - 0.06)],
                ];
                chart
                    .draw_series(
                        whisker
                            .into_iter()
                            .map(|line| PathElement::new(line, BLACK.stroke_width(1))),
                    )
                    .map_err(drawing)?;
            }
        }
    }
    Ok(())
}
