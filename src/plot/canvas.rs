//! What every picture shares: the embedded font, the colours, a PNG that appears whole or
//! not at all, the panel of lines and its legend.

use crate::output::AtomicFile;
use crate::output::cannot_write;
use anyhow::{anyhow, bail};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// The font family every picture uses (registered from the embedded DejaVu Sans).
pub(crate) const FONT: &str = "sans-serif";

/// A drawing area of a picture being drawn.
pub(crate) type Area<'a> = DrawingArea<BitMapBackend<'a>, Shift>;

/// Colours of the outcomes, in the order of `Outcome::ALL` (stable, tipped, sliding,
/// bouncing, diverged, held): green, red, orange, blue, black, purple.
pub(crate) const OUTCOME_COLOURS: [RGBColor; 6] = [
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(255, 127, 14),
    RGBColor(31, 119, 180),
    RGBColor(0, 0, 0),
    RGBColor(148, 103, 189),
];

/// Line colours of the series of one panel (x, y, z; or legs 0, 1, ...).
pub(crate) const SERIES_COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// The colour of what `[limits]` marks: the exceedance picture's limit lines, the envelope's
/// outline of cells where samples broke a limit.
pub(crate) const LIMIT_COLOUR: RGBColor = RGBColor(200, 0, 200);

/// Registers the embedded font once per process.
pub(crate) fn register_font() -> anyhow::Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok()
    });
    if ok {
        Ok(())
    } else {
        bail!("cannot load the embedded DejaVu Sans font")
    }
}

/// Draws a `width` x `height` picture with `draw` and writes it to `path` as PNG (under a
/// temporary name until it is complete).
pub(crate) fn save_png(
    path: &Path,
    (width, height): (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    register_font()?;
    let mut pixels = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        draw(&root)?;
        root.present().map_err(drawing)?;
    }
    let (file, mut out) = AtomicFile::create(path)?;
    use image::ImageEncoder as _;
    image::codecs::png::PngEncoder::new_with_quality(
        &mut out,
        image::codecs::png::CompressionType::Best,
        image::codecs::png::FilterType::Adaptive,
    )
    .write_image(&pixels, width, height, image::ColorType::Rgb8)
    .map_err(|e| cannot_write(path, e))?;
    std::io::Write::flush(&mut out).map_err(|e| cannot_write(path, e))?;
    file.commit(out)
}

/// A drawing error as an `anyhow` error.
pub(crate) fn drawing(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("cannot draw the picture: {e}")
}

/// A series of one panel: its legend label, colour and points.
pub(crate) struct Line {
    /// The legend's entry.
    pub(crate) label: String,
    /// The line's colour.
    pub(crate) colour: RGBColor,
    /// Its points, (x, y).
    pub(crate) points: Vec<(f64, f64)>,
}

impl Line {
    /// The points in pieces, cut where an angle wraps around (a jump of more than 180 deg
    /// between neighbours, as yaw makes at +-180 deg), so that no vertical line joins them.
    fn pieces(&self, wraps: bool) -> Vec<&[(f64, f64)]> {
        if !wraps {
            return vec![&self.points];
        }
        let mut pieces = Vec::new();
        let mut start = 0;
        for i in 1..self.points.len() {
            if (self.points[i].1 - self.points[i - 1].1).abs() > 180.0 {
                pieces.push(&self.points[start..i]);
                start = i;
            }
        }
        pieces.push(&self.points[start..]);
        pieces
    }
}

/// The range of `values` (finite ones), widened by `pad` of its length on each side; a
/// constant (or empty) one becomes its value plus or minus 1.
pub(crate) fn span(values: impl Iterator<Item = f64>, pad: f64) -> std::ops::Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return -1.0..1.0;
    }
    if hi - lo <= 1e-9 * hi.abs().max(1.0) {
        return lo - 1.0..hi + 1.0;
    }
    let p = pad * (hi - lo);
    lo - p..hi + p
}

/// Draws `lines` against a shared x axis in `area`, with a caption, axis labels and legend.
pub(crate) fn line_panel(
    area: &Area<'_>,
    caption: &str,
    axes: (&str, &str),
    x_range: std::ops::Range<f64>,
    lines: &[Line],
) -> anyhow::Result<()> {
    lines_in(area, caption, axes, x_range, y_span(lines), lines)
}

/// The y range of `lines`, padded by 5 % of it.
fn y_span(lines: &[Line]) -> std::ops::Range<f64> {
    span(
        lines.iter().flat_map(|l| l.points.iter().map(|p| p.1)),
        0.05,
    )
}

/// `line_panel` with its legend above the lines: the y axis reaches up by the legend's
/// height, so that no line runs under it (for panels whose lines fill their width).
pub(crate) fn line_panel_legend_clear(
    area: &Area<'_>,
    caption: &str,
    axes: (&str, &str),
    x_range: std::ops::Range<f64>,
    lines: &[Line],
) -> anyhow::Result<()> {
    let y = y_span(lines);
    // The plotting height: the panel less its caption (18 points: about 27 pixels with its
    // gap), the x labels (38) and the margins (2 x 8). The legend: 18 pixels a line (14-point
    // labels) and 14 of box and gap; the lines keep at least half the height.
    let plot_px = f64::from(area.dim_in_pixel().1) - 27.0 - 38.0 - 16.0;
    let legend_px = 18.0 * lines.len() as f64 + 14.0;
    let free = (1.0 - legend_px / plot_px).max(0.5);
    let top = y.start + (y.end - y.start) / free;
    lines_in(area, caption, axes, x_range, y.start..top, lines)
}

/// `line_panel` with the y axis spanning `y_range`.
fn lines_in(
    area: &Area<'_>,
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    x_range: std::ops::Range<f64>,
    y_range: std::ops::Range<f64>,
    lines: &[Line],
) -> anyhow::Result<()> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 18))
        .margin(8)
        .x_label_area_size(38)
        .y_label_area_size(78)
        .build_cartesian_2d(x_range, y_range)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 15))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(drawing)?;
    // Angles in degrees wrap at +-180: their lines break there.
    let wraps = y_desc.contains("(deg)");
    for l in lines {
        let colour = l.colour;
        for (k, piece) in l.pieces(wraps).into_iter().enumerate() {
            let drawn = chart
                .draw_series(LineSeries::new(
                    piece.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(drawing)?;
            if k == 0 {
                drawn.label(l.label.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2))
                });
            }
        }
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// A 2D chart of a picture.
/// A chart of two axes of numbers on a bitmap.
pub(crate) type Chart2d<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Draws the legend of `chart` (linear or log axes) at `position`, on a light box.
pub(crate) fn legend<'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, BitMapBackend<'a>, CT>,
    position: SeriesLabelPosition,
) -> anyhow::Result<()> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .label_font((FONT, 14))
        .draw()
        .map_err(drawing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_lines_break_where_they_wrap() {
        let line = Line {
            label: "yaw".into(),
            colour: BLACK,
            points: vec![
                (0.0, 170.0),
                (1.0, 179.0),
                (2.0, -179.0),
                (3.0, -170.0),
                (4.0, 175.0),
            ],
        };
        let pieces = line.pieces(true);
        assert_eq!(pieces.len(), 3);
        assert_eq!(pieces[0], &[(0.0, 170.0), (1.0, 179.0)][..]);
        assert_eq!(pieces[2], &[(4.0, 175.0)][..]);
        assert_eq!(line.pieces(false).len(), 1);
    }

    /// The legend's box in a panel's pixels: its top and bottom rows (the rows of its
    /// border's grey in a run of at least 100 pixels) and its left column.
    fn legend_box(pixels: &[u8], width: usize) -> (usize, usize, usize) {
        let grey = [160, 160, 160];
        let mut edges = Vec::new();
        for (y, row) in pixels.chunks(width * 3).enumerate() {
            let mut run = 0;
            for (x, p) in row.chunks(3).enumerate() {
                run = if p == grey { run + 1 } else { 0 };
                if run == 100 {
                    edges.push((y, x + 1 - run));
                    break;
                }
            }
        }
        let (top, left) = edges[0];
        (top, edges[edges.len() - 1].0, left)
    }

    /// The top row holding colour `c` left of column `before`.
    fn top_row_with(pixels: &[u8], width: usize, c: RGBColor, before: usize) -> Option<usize> {
        pixels
            .chunks(width * 3)
            .position(|row| row.chunks(3).take(before).any(|p| p == [c.0, c.1, c.2]))
    }

    /// A panel (of trace-thrust.png's size) whose three lines run at their top value across
    /// the whole time axis, the worst case for a legend in a corner: drawn with
    /// `line_panel_legend_clear`, the legend's box (its border's grey) lies wholly above
    /// every line; drawn with `line_panel`, it covers them.
    #[test]
    fn a_clear_legend_lies_above_the_lines() {
        register_font().unwrap();
        let (w, h) = (1100u32, 325u32);
        let lines: Vec<Line> = (0..3)
            .map(|k| Line {
                label: format!("line {k} with a long label"),
                colour: SERIES_COLOURS[k],
                points: vec![(0.0, 0.0), (0.5, 10.0 - k as f64), (100.0, 10.0 - k as f64)],
            })
            .collect();
        let draw = |clear: bool| {
            let mut pixels = vec![0u8; w as usize * h as usize * 3];
            {
                let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
                root.fill(&WHITE).unwrap();
                let panel = if clear {
                    line_panel_legend_clear
                } else {
                    line_panel
                };
                panel(&root, "panel", ("x", "y"), 0.0..100.0, &lines).unwrap();
                root.present().unwrap();
            }
            let (_, bottom, left) = legend_box(&pixels, w as usize);
            // Left of the box: the lines, not the legend's samples of them.
            let top_line = (0..3)
                .filter_map(|k| top_row_with(&pixels, w as usize, SERIES_COLOURS[k], left - 5))
                .min()
                .unwrap();
            (bottom, top_line)
        };
        let (legend_bottom, top_line) = draw(true);
        assert!(legend_bottom < top_line, "{legend_bottom} {top_line}");
        let (legend_bottom, top_line) = draw(false);
        assert!(legend_bottom >= top_line, "{legend_bottom} {top_line}");
    }
}
