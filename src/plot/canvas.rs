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
    (x_desc, y_desc): (&str, &str),
    x_range: std::ops::Range<f64>,
    lines: &[Line],
) -> anyhow::Result<()> {
    let y_range = span(
        lines.iter().flat_map(|l| l.points.iter().map(|p| p.1)),
        0.05,
    );
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

/// Draws the legend of `chart` at `position`, on a light box.
pub(crate) fn legend<'a>(
    chart: &mut Chart2d<'a, 'a>,
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
}
