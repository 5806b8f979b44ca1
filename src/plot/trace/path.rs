//! The 3D path of the CG and the footpads over the slope plane, on equal scales.

use super::series::Series;
use crate::plot::canvas::{Area, FONT, SERIES_COLOURS, drawing, span};
use plotters::coord::ranged3d::Cartesian3d;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Colours of the axis names X_I, Y_I, Z_I of the 3D path (red, green, blue as in most 3D
/// tools; darker than any series colour, and none of them).
const AXIS_COLOURS: [RGBColor; 3] = [
    RGBColor(170, 20, 20),
    RGBColor(20, 120, 20),
    RGBColor(20, 20, 170),
];

/// The 3D chart of the path: its axes are (X_I, Z_I, Y_I).
type Chart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian3d<RangedCoordf64, RangedCoordf64, RangedCoordf64>,
>;

/// A path in I: its label and its points.
type Path3 = (String, Vec<(f64, f64, f64)>);

/// The CG's path and every footpad's.
fn paths(tr: &Series) -> anyhow::Result<Vec<Path3>> {
    let col = |n: &str| tr.trace.column_named(n);
    let path = |x: &str, y: &str, z: &str| -> anyhow::Result<Vec<(f64, f64, f64)>> {
        let (x, y, z) = (col(x)?, col(y)?, col(z)?);
        Ok((0..x.len()).map(|i| (x[i], y[i], z[i])).collect())
    };
    let mut paths = vec![("CG".to_string(), path("x_m", "y_m", "z_m")?)];
    for k in 0..tr.trace.legs {
        paths.push((
            format!("footpad {k}"),
            path(
                &format!("leg{k}_tip_x_m"),
                &format!("leg{k}_tip_y_m"),
                &format!("leg{k}_tip_z_m"),
            )?,
        ));
    }
    Ok(paths)
}

/// The CG and footpad paths in 3D over a patch of the slope plane. Equal scales on all
/// axes, so that the path's shape is true.
pub(super) fn path_3d(root: &Area<'_>, tr: &Series) -> anyhow::Result<()> {
    let paths = paths(tr)?;
    let all = || paths.iter().flat_map(|p| p.1.iter());
    let rx = span(all().map(|p| p.0), 0.0);
    let ry = span(all().map(|p| p.1), 0.0);
    let rz = span(all().map(|p| p.2), 0.0);
    let half = [&rx, &ry, &rz]
        .iter()
        .map(|r| 0.5 * (r.end - r.start))
        .fold(0.5, f64::max)
        * 1.05;
    let mid = |r: &std::ops::Range<f64>| 0.5 * (r.start + r.end);
    let (cx, cy, cz) = (mid(&rx), mid(&ry), mid(&rz));
    // plotters draws its second axis upwards: the chart's axes are (X_I, Z_I, Y_I).
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Path of the CG and footpads, {}", tr.about()),
            (FONT, 20),
        )
        .margin(20)
        .build_cartesian_3d(
            cx - half..cx + half,
            cz - half..cz + half,
            cy - half..cy + half,
        )
        .map_err(drawing)?;
    chart.with_projection(|mut p| {
        p.yaw = 0.7;
        p.pitch = 0.35;
        p.scale = 0.85;
        p.into_matrix()
    });
    chart
        .configure_axes()
        .light_grid_style(RGBColor(235, 235, 235))
        .max_light_lines(4)
        .label_style((FONT, 12))
        .draw()
        .map_err(drawing)?;
    // The slope plane n . p = 0 (its mean, on rough terrain) as a grid of lines.
    slope_plane(&mut chart, tr.normal, (cx, cy, cz), half)?;
    for (k, (label, pts)) in paths.iter().enumerate() {
        let colour = if k == 0 {
            BLACK
        } else {
            SERIES_COLOURS[(k - 1) % SERIES_COLOURS.len()]
        };
        let width = if k == 0 { 3 } else { 1 };
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.2, p.1)),
                colour.stroke_width(width),
            ))
            .map_err(drawing)?
            .label(label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(width))
            });
    }
    marks(&mut chart, &paths[0].1, (cx, cy, cz), half)?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(160, 160, 160))
        .label_font((FONT, 13))
        .draw()
        .map_err(drawing)?;
    Ok(())
}

/// The slope plane of normal `n` as a grid of lines over the chart's square around
/// `(cx, cy, cz)` of half-side `half` (none for a plane seen edge on).
fn slope_plane(
    chart: &mut Chart<'_, '_>,
    n: [f64; 3],
    (cx, cy, cz): (f64, f64, f64),
    half: f64,
) -> anyhow::Result<()> {
    if n[2] > 1e-6 {
        let grey = RGBColor(170, 170, 170);
        let height = |x: f64, y: f64| -(n[0] * x + n[1] * y) / n[2];
        let steps = 8;
        for i in 0..=steps {
            let f = -half + 2.0 * half * f64::from(i) / f64::from(steps);
            for line in [
                [(cx + f, cy - half), (cx + f, cy + half)],
                [(cx - half, cy + f), (cx + half, cy + f)],
            ] {
                let pts: Vec<(f64, f64, f64)> = (0..=20)
                    .map(|j| {
                        let s = f64::from(j) / 20.0;
                        let x = line[0].0 + s * (line[1].0 - line[0].0);
                        let y = line[0].1 + s * (line[1].1 - line[0].1);
                        (x, height(x, y), y)
                    })
                    .filter(|p| (p.1 - cz).abs() <= half)
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, grey.stroke_width(1)))
                    .map_err(drawing)?;
            }
        }
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64, f64)>>())
            .map_err(drawing)?
            .label("slope plane")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], grey.stroke_width(1))
            });
    }
    Ok(())
}

/// The start and end of the CG's path `cg`, and the axis names.
fn marks(
    chart: &mut Chart<'_, '_>,
    cg: &[(f64, f64, f64)],
    (cx, cy, cz): (f64, f64, f64),
    half: f64,
) -> anyhow::Result<()> {
    // Start and end of the CG's path.
    for (p, what) in [(cg[0], "start"), (cg[cg.len() - 1], "end")] {
        chart
            .draw_series([EmptyElement::at((p.0, p.2, p.1))
                + Circle::new((0, 0), 5, BLACK.filled())
                + Text::new(what, (8, -18), (FONT, 15))])
            .map_err(drawing)?;
    }
    // Axis names beside the middle of the edges that carry their tick labels (seen from
    // this side, X_I ticks run along the front-left edge at Y_I max, Y_I ticks along the
    // front-right edge at X_I max), in the colours of AXIS_COLOURS.
    for ((text, at, offset), colour) in [
        ("X_I (m)", (cx, cz - half, cy + half), (-110, 40)),
        ("Y_I (m)", (cx + half, cz - half, cy), (50, 40)),
        ("Z_I, up (m)", (cx - half, cz + half, cy + half), (-40, -30)),
    ]
    .into_iter()
    .zip(AXIS_COLOURS)
    {
        chart
            .draw_series([EmptyElement::at(at)
                + Text::new(text, offset, (FONT, 15).into_font().color(&colour))])
            .map_err(drawing)?;
    }
    Ok(())
}
