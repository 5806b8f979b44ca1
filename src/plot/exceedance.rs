//! The load exceedance picture of a sweep (`exceedance`): per quantity a panel of the
//! probability that a sample's value exceeds x, log scale, per leg and over all legs with
//! its 95 % band, the 99 % and 99.9 % levels the design values are read at, and with
//! `[limits]` each limit as a labelled vertical line.

use super::canvas::{Area, FONT, LIMIT_COLOUR, SERIES_COLOURS, drawing, legend, span};
use crate::exceedance::{DESIGN_LEVELS, LimitMark, Quantity, curve};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Points of each curve: enough for a smooth line on a panel 600 pixels wide.
const POINTS: usize = 300;

/// Draws one panel per quantity in `root`, two across, each with the limits of `marks` on
/// its axis.
pub(super) fn exceedance(
    root: &Area<'_>,
    quantities: &[Quantity],
    marks: &[LimitMark],
    about: &str,
) -> anyhow::Result<()> {
    let rows = quantities.len().div_ceil(2);
    let (title, body) = root.split_vertically(34);
    title
        .titled(
            &format!("Load exceedance: P(value > x) per sample ({about})"),
            (FONT, 20),
        )
        .map_err(drawing)?;
    let panels = body.split_evenly((rows, 2));
    for (q, area) in quantities.iter().zip(&panels) {
        let limit = marks.iter().find(|m| m.key == q.key);
        panel(area, q, limit)?;
    }
    Ok(())
}

/// The panel of one quantity, with its limit where `[limits]` gives one.
fn panel(area: &Area<'_>, q: &Quantity, limit: Option<&LimitMark>) -> anyhow::Result<()> {
    let n = q.overall.len().max(1);
    let overall = curve(&q.overall, POINTS);
    let legs: Vec<_> = q.legs.iter().map(|v| curve(v, POINTS)).collect();
    // Down to one sample in n, a little below so that the last step shows.
    let y_min = 0.5 / n as f64;
    let x = span(
        overall
            .iter()
            .chain(legs.iter().flatten())
            .map(|p| p.0)
            .chain(q.overall.last().copied())
            .chain(limit.map(|m| m.value)),
        0.03,
    );
    let mut chart = ChartBuilder::on(area)
        .caption(q.name, (FONT, 17))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x.clone(), (y_min..1.0).log_scale())
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(format!("{} ({})", q.name, q.unit))
        .y_desc("P(value > x)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    // The 95 % band of the overall curve, then the levels, the legs, the overall line.
    let band: Vec<(f64, f64)> = overall
        .iter()
        .map(|p| (p.0, p.3))
        .chain(overall.iter().rev().map(|p| (p.0, p.2.max(y_min))))
        .collect();
    chart
        .draw_series(std::iter::once(Polygon::new(
            band,
            RGBColor(200, 200, 200).mix(0.6),
        )))
        .map_err(drawing)?
        .label("95 % band")
        .legend(|(x, y)| {
            Rectangle::new(
                [(x, y - 5), (x + 18, y + 5)],
                RGBColor(200, 200, 200).filled(),
            )
        });
    for level in DESIGN_LEVELS {
        let p = 1.0 - level;
        if p >= y_min {
            chart
                .draw_series(DashedLineSeries::new(
                    [(x.start, p), (x.end, p)],
                    6,
                    4,
                    RGBColor(120, 120, 120).stroke_width(1),
                ))
                .map_err(drawing)?;
        }
    }
    for (k, c) in legs.iter().enumerate() {
        let colour = SERIES_COLOURS[k % SERIES_COLOURS.len()];
        chart
            .draw_series(LineSeries::new(
                c.iter().map(|p| (p.0, p.1)),
                colour.stroke_width(1),
            ))
            .map_err(drawing)?
            .label(format!("leg {k}"))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
            });
    }
    let label = if q.legs.is_empty() {
        "samples"
    } else {
        "all legs (largest)"
    };
    chart
        .draw_series(LineSeries::new(
            overall.iter().map(|p| (p.0, p.1)),
            BLACK.stroke_width(3),
        ))
        .map_err(drawing)?
        .label(label)
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(3)));
    if let Some(m) = limit {
        draw_limit(&mut chart, m, &x, y_min)?;
    }
    // The lower left is empty: small values are exceeded often.
    legend(&mut chart, SeriesLabelPosition::LowerLeft)
}

/// The limit `m` as a vertical line over the panel's height, labelled at its top on the
/// side with more room (the x range `x`).
fn draw_limit<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, LogCoord<f64>>>,
    m: &LimitMark,
    x: &std::ops::Range<f64>,
    y_min: f64,
) -> anyhow::Result<()> {
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(m.value, y_min), (m.value, 1.0)],
            LIMIT_COLOUR.stroke_width(2),
        )))
        .map_err(drawing)?;
    let left = m.value > 0.5 * (x.start + x.end);
    let anchor = if left { HPos::Right } else { HPos::Left };
    let style = TextStyle::from((FONT, 13))
        .color(&LIMIT_COLOUR)
        .pos(Pos::new(anchor, VPos::Top));
    // Six pixels off the line, four below the top edge.
    let dx = if left { -6 } else { 6 };
    chart
        .draw_series(std::iter::once(
            EmptyElement::at((m.value, 1.0)) + Text::new(m.label.clone(), (dx, 4), style),
        ))
        .map_err(drawing)?;
    Ok(())
}
