//! The picture of `touchdown envelope`: per panel (slope band, and facing) the cells of the
//! plane coloured by their stable share, the 99 %-stable boundary of each row with its
//! 95 % interval, the cells where samples broke a limit outlined; a colour bar and a legend.

use super::canvas::{Area, Chart2d, FONT, drawing, save_png};
use crate::envelope::{Envelope, Facing, Panel, panel_title};
use crate::stats::Allowable;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Panels side by side at most.
const COLUMNS: usize = 4;

/// Panel size, pixels.
const PANEL: (u32, u32) = (470, 420);

/// Heights of the title and legend strips and width of the colour bar's strip, pixels.
const TITLE: u32 = 44;
const LEGEND: u32 = 100;
const BAR: u32 = 120;

/// The narrowest picture, pixels: the legend's longest line.
const MIN_WIDTH: u32 = 820;

/// The colour of cells without samples.
const EMPTY: RGBColor = RGBColor(238, 238, 238);

/// The outline of cells where samples broke a limit.
const LIMIT: RGBColor = super::canvas::LIMIT_COLOUR;

/// The share of a cell's samples that broke a limit: darker than the outline, to read on
/// any cell.
const LIMIT_TEXT: RGBColor = RGBColor(110, 0, 130);

/// The boundary's colour.
const BOUNDARY: RGBColor = RGBColor(0, 0, 0);

/// The columns and rows of panels of a picture of `bands` slope bands of `facings` each.
fn layout(bands: usize, facings: usize) -> (usize, usize) {
    let cols = bands.clamp(1, COLUMNS);
    (cols, bands.div_ceil(cols) * facings)
}

/// The size in pixels, width and height, of the picture of an envelope of `bands` slope
/// bands of `facings` panels each (for the memory it takes, before it is drawn).
#[must_use]
pub(crate) fn envelope_picture_size(bands: usize, facings: usize) -> (u64, u64) {
    let (cols, rows) = layout(bands, facings);
    // Wide enough for the legend's lines.
    let width = (u64::from(PANEL.0) * cols as u64 + u64::from(BAR)).max(u64::from(MIN_WIDTH));
    let height = u64::from(TITLE) + u64::from(PANEL.1) * rows as u64 + u64::from(LEGEND);
    (width, height)
}

/// Writes the picture of `e` to `out` (PNG).
pub(crate) fn envelope_chart(out: &Path, e: &Envelope) -> anyhow::Result<()> {
    let facings = if e.panels.iter().any(|p| p.facing != Facing::All) {
        2
    } else {
        1
    };
    let bands = e.panels.len() / facings;
    let (cols, rows) = layout(bands, facings);
    let (width, height) = envelope_picture_size(bands, facings);
    let size = |n: u64| {
        u32::try_from(n).map_err(|_| anyhow::anyhow!("the picture would be {n} pixels across"))
    };
    let (width, height) = (size(width)?, size(height)?);
    save_png(out, (width, height), |root| {
        let (title, rest) = root.split_vertically(TITLE);
        let (body, foot) = rest.split_vertically(PANEL.1 * rows as u32);
        let (grid, bar) = body.split_horizontally(width - BAR);
        title
            .titled(
                &format!(
                    "Touchdown envelope: {}, {} of {} samples, seed {}{}",
                    e.path.display(),
                    e.samples(),
                    e.rows,
                    e.seed,
                    e.interrupted
                        .as_ref()
                        .map_or(String::new(), |_| " (an interrupted sweep)".to_string())
                ),
                (FONT, 20),
            )
            .map_err(drawing)?;
        let areas = grid.split_evenly((rows, cols));
        for (k, p) in e.panels.iter().enumerate() {
            let (band, facing) = (k / facings, k % facings);
            let at = (band / cols) * facings + facing;
            panel(&areas[at * cols + band % cols], e, p)?;
        }
        colour_bar(&bar)?;
        legend(&foot, e)
    })
}

/// The colour of a stable share `p` in [0, 1]: red through yellow to green, light enough
/// at the red end for the cells' numbers to read.
fn share_colour(p: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [240.0, 96.0, 72.0]),
        (0.25, [253.0, 174.0, 97.0]),
        (0.5, [254.0, 224.0, 139.0]),
        (0.75, [166.0, 217.0, 106.0]),
        (1.0, [26.0, 152.0, 80.0]),
    ];
    let p = p.clamp(0.0, 1.0);
    let k = STOPS.iter().rposition(|s| s.0 <= p).unwrap_or(0).min(3);
    let ((a, ca), (b, cb)) = (STOPS[k], STOPS[k + 1]);
    let t = (p - a) / (b - a);
    let c = |i: usize| (ca[i] + t * (cb[i] - ca[i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// One panel: the cells, the boundary with its interval, the limit marks.
fn panel(area: &Area<'_>, e: &Envelope, p: &Panel) -> anyhow::Result<()> {
    let mut caption = format!("{}: {} samples", panel_title(p), p.samples());
    if e.limits {
        caption.push_str(&format!(", {} broke a limit", p.limits_broken()));
    }
    if !p
        .rows
        .iter()
        .any(|r| matches!(r.boundary, Allowable::Slope { .. }))
    {
        caption.push_str("; no 99 % row");
    }
    // Smaller type for a longer caption, so that it stays over its panel (DejaVu Sans is
    // about 0.45 of its size wide a character, measured).
    let width = f64::from(area.dim_in_pixel().0) - 20.0;
    let size = (width / (0.47 * caption.chars().count() as f64)).clamp(10.0, 16.0);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, size))
        .margin(10)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(e.x.lo..e.x.hi, e.y.lo..e.y.hi)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(e.x.label())
        .y_desc(e.y.label())
        .x_labels(6)
        .y_labels(6)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(drawing)?;
    let (nx, ny) = (e.x.bins, e.y.bins);
    let rect = |i: usize, j: usize| {
        [
            (e.x.edge(i), e.y.edge(j)),
            (e.x.edge(i + 1), e.y.edge(j + 1)),
        ]
    };
    chart
        .draw_series(
            (0..ny)
                .flat_map(|j| (0..nx).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let c = p.cell(i, j, nx);
                    let colour = match c.samples() {
                        0 => EMPTY,
                        n if n < FEW => pale(share_colour(c.stable() as f64 / n as f64)),
                        n => share_colour(c.stable() as f64 / n as f64),
                    };
                    Rectangle::new(rect(i, j), colour.filled())
                }),
        )
        .map_err(drawing)?;
    share_labels(&mut chart, e, p)?;
    limit_marks(&mut chart, e, p)?;
    boundary(&mut chart, e, p)
}

/// Cells with fewer samples than this are drawn pale: their share is uncertain by more
/// than +-20 % (the 95 % Wilson interval of 10 in 20 is 30-70 %).
const FEW: u64 = 20;

/// A colour blended halfway to white.
fn pale(c: RGBColor) -> RGBColor {
    let m = |v: u8| ((u16::from(v) + 255) / 2) as u8;
    RGBColor(m(c.0), m(c.1), m(c.2))
}

/// Each cell's stable share in percent, where the cells are large enough for the text.
fn share_labels(chart: &mut Chart2d<'_, '_>, e: &Envelope, p: &Panel) -> anyhow::Result<()> {
    let (nx, ny) = (e.x.bins, e.y.bins);
    let (w, h) = chart.plotting_area().dim_in_pixel();
    if f64::from(w) / (nx as f64) < 24.0 || f64::from(h) / (ny as f64) < 14.0 {
        return Ok(());
    }
    let dark = RGBColor(40, 40, 40);
    let layout = RowLayout::of(f64::from(h) / ny as f64);
    for j in 0..ny {
        for i in 0..nx {
            let c = p.cell(i, j, nx);
            if c.samples() == 0 {
                continue;
            }
            let share = 100.0 * c.stable() as f64 / c.samples() as f64;
            let text = if share > 0.0 && share < 0.5 {
                "<1".to_string()
            } else if (99.5..100.0).contains(&share) {
                ">99".to_string()
            } else {
                format!("{share:.0}")
            };
            // Above the whisker, and above the limit mark's share in a cell that has one.
            let up = if c.limits_broken > 0 {
                layout.share_with_limit
            } else {
                layout.share
            };
            let at = (
                0.5 * (e.x.edge(i) + e.x.edge(i + 1)),
                e.y.edge(j) + up * (e.y.edge(j + 1) - e.y.edge(j)),
            );
            let style = (FONT, 10)
                .into_font()
                .color(&dark)
                .pos(Pos::new(HPos::Center, VPos::Center));
            chart
                .draw_series(std::iter::once(Text::new(text, at, style)))
                .map_err(drawing)?;
        }
    }
    Ok(())
}

/// The cells where samples broke a limit: outlined, with the share of their samples that
/// did where the cell is wide enough for it.
fn limit_marks(chart: &mut Chart2d<'_, '_>, e: &Envelope, p: &Panel) -> anyhow::Result<()> {
    let nx = e.x.bins;
    let (w, h) = chart.plotting_area().dim_in_pixel();
    let width_px = f64::from(w) / nx as f64;
    let layout = RowLayout::of(f64::from(h) / e.y.bins as f64);
    for j in 0..e.y.bins {
        for i in 0..nx {
            let c = p.cell(i, j, nx);
            if c.limits_broken == 0 {
                continue;
            }
            let (x0, x1, y0, y1) = (e.x.edge(i), e.x.edge(i + 1), e.y.edge(j), e.y.edge(j + 1));
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x0, y0), (x1, y1)],
                    LIMIT.stroke_width(2),
                )))
                .map_err(drawing)?;
            if width_px >= 24.0 {
                let share = 100.0 * c.limits_broken as f64 / c.samples() as f64;
                let style = (FONT, 10)
                    .into_font()
                    .color(&LIMIT_TEXT)
                    .pos(Pos::new(HPos::Center, VPos::Center));
                chart
                    .draw_series(std::iter::once(Text::new(
                        format!("{share:.0}%"),
                        (0.5 * (x0 + x1), y0 + layout.limit_share * (y1 - y0)),
                        style,
                    )))
                    .map_err(drawing)?;
            }
        }
    }
    Ok(())
}

/// The whisker's caps, pixels tall.
const WHISKER_CAP_PX: u32 = 6;

/// Half the height of a cell's text (10 px type), pixels.
const TEXT_HALF_PX: f64 = 5.0;

/// Where the marks of a row of cells go, as fractions of its height from its foot: the
/// boundary's whisker at the foot, the share of samples that broke a limit above it and
/// the stable share above both, a pixel apart (as far as the row is tall enough: one
/// of at least 32 pixels holds all three apart, one of at least 24 the whisker and the
/// stable share).
#[derive(Debug, Clone, Copy, PartialEq)]
struct RowLayout {
    /// The whisker's middle.
    whisker: f64,
    /// The middle of the share of samples that broke a limit.
    limit_share: f64,
    /// The middle of the stable share in a cell without a broken limit.
    share: f64,
    /// The same in a cell with one, above the limit share.
    share_with_limit: f64,
}

impl RowLayout {
    /// The layout of a row `height_px` pixels tall.
    fn of(height_px: f64) -> RowLayout {
        let px = |p: f64| p / height_px.max(1.0);
        let whisker_px = f64::from(WHISKER_CAP_PX) / 2.0 + 1.0;
        let above_whisker_px = whisker_px + f64::from(WHISKER_CAP_PX) / 2.0 + 1.0 + TEXT_HALF_PX;
        let limit_share = px(above_whisker_px).max(0.3);
        RowLayout {
            whisker: px(whisker_px).min(0.5),
            limit_share,
            share: px(above_whisker_px).max(0.5),
            share_with_limit: (limit_share + px(2.0 * TEXT_HALF_PX + 1.0)).max(0.7),
        }
    }
}

/// Each row's boundary: a line at its x across the row (joined between neighbouring rows
/// that have one), its 95 % interval as a grey band across the row and a whisker at its
/// foot, below the cells' labels.
fn boundary(chart: &mut Chart2d<'_, '_>, e: &Envelope, p: &Panel) -> anyhow::Result<()> {
    let layout = RowLayout::of(f64::from(chart.plotting_area().dim_in_pixel().1) / e.y.bins as f64);
    let mut path: Vec<(f64, f64)> = Vec::new();
    for (j, r) in p.rows.iter().enumerate() {
        let (y0, y1) = (e.y.edge(j), e.y.edge(j + 1));
        let Allowable::Slope {
            slope_deg: x,
            low_deg,
            high_deg,
        } = r.boundary
        else {
            if path.len() > 1 {
                draw_path(chart, &path)?;
            }
            path.clear();
            continue;
        };
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(low_deg, y0), (high_deg, y1)],
                BOUNDARY.mix(0.22).filled(),
            )))
            .map_err(drawing)?;
        chart
            .draw_series(std::iter::once(ErrorBar::new_horizontal(
                y0 + layout.whisker * (y1 - y0),
                low_deg,
                x,
                high_deg,
                BOUNDARY.stroke_width(1),
                WHISKER_CAP_PX,
            )))
            .map_err(drawing)?;
        path.extend([(x, y0), (x, y1)]);
    }
    if path.len() > 1 {
        draw_path(chart, &path)?;
    }
    Ok(())
}

/// The boundary's line through `points`.
fn draw_path(chart: &mut Chart2d<'_, '_>, points: &[(f64, f64)]) -> anyhow::Result<()> {
    chart
        .draw_series(std::iter::once(PathElement::new(
            points.to_vec(),
            BOUNDARY.stroke_width(3),
        )))
        .map_err(drawing)?;
    Ok(())
}

/// The colour bar of the stable share.
fn colour_bar(area: &Area<'_>) -> anyhow::Result<()> {
    let mut chart = ChartBuilder::on(area)
        .caption("stable share", (FONT, 14))
        .margin_top(60)
        .margin_bottom(70)
        .margin_left(10)
        .margin_right(10)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(11)
        .y_label_formatter(&|v| format!("{:.0} %", 100.0 * v))
        .label_style((FONT, 12))
        .draw()
        .map_err(drawing)?;
    chart
        .draw_series((0..200).map(|k| {
            let (a, b) = (f64::from(k) / 200.0, f64::from(k + 1) / 200.0);
            Rectangle::new([(0.0, a), (1.0, b)], share_colour(0.5 * (a + b)).filled())
        }))
        .map_err(drawing)?;
    Ok(())
}

/// The legend strip: what the line, the band, the numbers and the outlines mean, a line
/// each.
fn legend(area: &Area<'_>, e: &Envelope) -> anyhow::Result<()> {
    let style = (FONT, 14).into_font();
    let x0 = 20;
    let line = |k: i32| 10 + 21 * k;
    area.draw(&PathElement::new(
        vec![(x0, line(0) + 8), (x0 + 30, line(0) + 8)],
        BOUNDARY.stroke_width(3),
    ))
    .map_err(drawing)?;
    area.draw(&Rectangle::new(
        [(x0, line(1) + 1), (x0 + 30, line(1) + 15)],
        BOUNDARY.mix(0.22).filled(),
    ))
    .map_err(drawing)?;
    let mut texts = vec![
        "99 %-stable boundary of a row: the largest x with ≥ 99 % of the row's samples at or \
         below it stable"
            .to_string(),
        "its 95 % interval (band and whisker); no line: no such x, or too few samples (see \
         the table)"
            .to_string(),
        format!("numbers: stable share (%); pale: fewer than {FEW} samples; grey: no samples"),
    ];
    if e.limits {
        area.draw(&Rectangle::new(
            [(x0, line(3) + 1), (x0 + 30, line(3) + 15)],
            LIMIT.stroke_width(2),
        ))
        .map_err(drawing)?;
        texts
            .push("cells where samples broke a limit (limits_broken), with their share (%)".into());
    }
    for (k, t) in texts.into_iter().enumerate() {
        area.draw(&Text::new(t, (x0 + 40, line(k as i32)), style.clone()))
            .map_err(drawing)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{RowLayout, TEXT_HALF_PX, WHISKER_CAP_PX};

    #[test]
    fn the_whisker_covers_no_label_of_its_row() {
        // Pixels from the row's foot: the whisker's caps, each label's text, apart and in
        // the row, for every row tall enough (24 pixels without a limit share, 32 with).
        for h in 24..200 {
            let h = f64::from(h);
            let l = RowLayout::of(h);
            let cap = f64::from(WHISKER_CAP_PX) / 2.0;
            let whisker = (h * l.whisker - cap, h * l.whisker + cap);
            let text = |at: f64| (h * at - TEXT_HALF_PX, h * at + TEXT_HALF_PX);
            let apart = |a: (f64, f64), b: (f64, f64)| a.1 < b.0 || b.1 < a.0;
            let inside = |a: (f64, f64)| a.0 >= 0.0 && a.1 <= h;
            assert!(inside(whisker) && inside(text(l.share)), "{h}: {l:?}");
            assert!(apart(whisker, text(l.share)), "{h}: {l:?}");
            if h >= 32.0 {
                let (limit, share) = (text(l.limit_share), text(l.share_with_limit));
                assert!(inside(limit) && inside(share), "{h}: {l:?}");
                assert!(
                    apart(whisker, limit) && apart(whisker, share) && apart(limit, share),
                    "{h}: {l:?}"
                );
            }
        }
    }
}
