//! The picture of `touchdown site`: two equirectangular maps of the body side by side, each
//! facet drawn as its triangle in (longitude, latitude). Left, P(stable) on a perceptual
//! scale with the landing sites (P(stable) >= `SAFE_P_STABLE`) in a colour of their own and
//! grey where a facet has no shares; right, the slope. The colour scales are public: the 3D
//! page (`crate::view::site`) colours the body with the same ones.
//!
//! A triangle that crosses the +-180 deg seam is drawn on both sides of the map, each copy
//! cut at the frame; a triangle with a vertex on the spin axis reaches the map's top or
//! bottom edge along the longitudes of its other two vertices, and one around a pole covers
//! the map's width above (or below) its edges.

use super::canvas::{Area, Chart2d, FONT, drawing, save_png};
use crate::site::{SAFE_P_STABLE, Site};
use anyhow::bail;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// The picture's size, pixels.
const SIZE: (u32, u32) = (1800, 700);
/// Height of the title strip, pixels.
const TITLE: u32 = 46;
/// Width of each map's colour-bar strip, pixels.
const BAR: u32 = 150;

/// The colour of facets without shares (and of values that are not finite).
pub const NO_SHARES: [u8; 3] = [170, 170, 170];

/// The colour of landing sites: facets with P(stable) >= `SAFE_P_STABLE` (a bluish green,
/// a hue the P(stable) scale never takes).
pub const SAFE: [u8; 3] = [0, 158, 115];

/// The P(stable) scale below `SAFE_P_STABLE`, from 0 to 1: matplotlib's "inferno" (black,
/// purple, red, orange, light yellow), perceptually uniform; evenly spaced stops.
pub const P_STABLE_SCALE: [[u8; 3]; 9] = [
    [0, 0, 4],
    [31, 12, 72],
    [85, 15, 109],
    [136, 34, 106],
    [186, 54, 85],
    [227, 89, 51],
    [249, 140, 10],
    [249, 201, 50],
    [252, 255, 164],
];

/// The slope and gravity scale, from its bottom to its top: matplotlib's "viridis" (dark
/// blue, green, yellow), perceptually uniform; evenly spaced stops.
pub const SLOPE_SCALE: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 82, 139],
    [44, 113, 142],
    [33, 145, 140],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

/// The colour at `t` in [0, 1] (clamped) of a scale of evenly spaced `stops`, interpolated
/// linearly; `NO_SHARES` when `t` is not finite or there are no stops.
#[must_use]
pub fn scale_colour(stops: &[[u8; 3]], t: f64) -> [u8; 3] {
    if !t.is_finite() || stops.is_empty() {
        return NO_SHARES;
    }
    let last = stops.len() - 1;
    let x = t.clamp(0.0, 1.0) * last as f64;
    let k = (x.floor() as usize).min(last.saturating_sub(1));
    let (a, b) = (stops[k], stops[(k + 1).min(last)]);
    let f = x - k as f64;
    let mix = |i: usize| (f64::from(a[i]) + f * (f64::from(b[i]) - f64::from(a[i]))).round() as u8;
    [mix(0), mix(1), mix(2)]
}

/// The colour of a facet's P(stable): `SAFE` at `SAFE_P_STABLE` or above, the P(stable)
/// scale below it, `NO_SHARES` without shares or when it is not finite.
#[must_use]
pub fn p_stable_colour(p: Option<f64>) -> [u8; 3] {
    match p {
        Some(p) if p.is_finite() && p >= SAFE_P_STABLE => SAFE,
        Some(p) => scale_colour(&P_STABLE_SCALE, p),
        None => NO_SHARES,
    }
}

/// The top of the slope scale, deg: the largest finite slope rounded up to a multiple of
/// 10, at least 30.
#[must_use]
pub fn slope_top_deg(site: &Site) -> f64 {
    let top = site
        .facets
        .iter()
        .map(|f| f.slope_deg)
        .filter(|s| s.is_finite())
        .fold(0.0f64, f64::max);
    ((top / 10.0).ceil() * 10.0).max(30.0)
}

/// The mean slope over the surface, weighted by the facets' areas, deg (facets whose slope
/// or area is not finite left out); `None` if no facet counts.
fn mean_slope_deg(site: &Site) -> Option<f64> {
    let (mut sum, mut area) = (0.0, 0.0);
    for f in &site.facets {
        if f.slope_deg.is_finite() && f.area_m2.is_finite() && f.area_m2 > 0.0 {
            sum += f.area_m2 * f.slope_deg;
            area += f.area_m2;
        }
    }
    (area > 0.0).then(|| sum / area)
}

/// Writes the map picture of `site` to `path` (PNG): P(stable) and the slope per facet in
/// longitude and latitude. Refuses a site without facets, with as many triangles as facets
/// missing or a triangle naming no vertex.
pub fn site_map(site: &Site, path: &Path) -> anyhow::Result<()> {
    let shapes = map_shapes(site)?;
    let p_colours: Vec<[u8; 3]> = site
        .facets
        .iter()
        .map(|f| p_stable_colour(f.p_stable().map(|s| s.p)))
        .collect();
    let top = slope_top_deg(site);
    let slope_colours: Vec<[u8; 3]> = site
        .facets
        .iter()
        .map(|f| scale_colour(&SLOPE_SCALE, f.slope_deg / top))
        .collect();
    let b = &site.body;
    let title = format!(
        "Landing sites on {}: density {} kg/m³, spin period {} h, {} facets",
        b.name,
        short(b.density_kg_m3),
        short(b.spin_period_h),
        site.facets.len()
    );
    let safe = format!(
        "P(stable) ≥ {SAFE_P_STABLE} on {:.1} % of the surface",
        100.0 * site.safe_area_fraction()
    );
    let mean = mean_slope_deg(site).map_or("no slopes".into(), |m| {
        format!("area-weighted mean {m:.1}°")
    });
    save_png(path, SIZE, |root| {
        let (head, rest) = root.split_vertically(TITLE);
        head.titled(&title, (FONT, 22)).map_err(drawing)?;
        let halves = rest.split_evenly((1, 2));
        let (map, bar) = halves[0].split_horizontally(SIZE.0 / 2 - BAR);
        draw_map(&map, &safe, &shapes, &p_colours)?;
        colour_bar(&bar, "P(stable)", 1.0, &|t| p_stable_colour(Some(t)), true)?;
        let (map, bar) = halves[1].split_horizontally(SIZE.0 / 2 - BAR);
        draw_map(
            &map,
            &format!("slope (deg), {mean}"),
            &shapes,
            &slope_colours,
        )?;
        colour_bar(
            &bar,
            "slope (deg)",
            top,
            &|v| scale_colour(&SLOPE_SCALE, v / top),
            false,
        )
    })
}

/// A number for a title: up to 4 significant digits, no trailing zeros.
fn short(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A point of the map: longitude and latitude, deg.
type LonLat = (f64, f64);

/// Each facet's pieces on the map, in (longitude, latitude): its triangle (a quadrilateral
/// where a vertex lies on the spin axis, a band to the map's edge where it rings a pole),
/// cut at the frame and drawn once more on the other side where it crosses the seam.
fn map_shapes(site: &Site) -> anyhow::Result<Vec<Vec<Vec<LonLat>>>> {
    let b = &site.body;
    if site.facets.is_empty() {
        bail!("the landing-site map of {} has no facets to draw", b.name);
    }
    if b.triangles.len() != site.facets.len() {
        bail!(
            "the landing-site map of {} has {} facets but {} triangles",
            b.name,
            site.facets.len(),
            b.triangles.len()
        );
    }
    let mut shapes = Vec::with_capacity(site.facets.len());
    for (k, (facet, t)) in site.facets.iter().zip(&b.triangles).enumerate() {
        let mut corners = [[0.0; 3]; 3];
        for (c, &i) in corners.iter_mut().zip(t) {
            *c = *b.vertices.get(i as usize).ok_or_else(|| {
                anyhow::anyhow!(
                    "triangle {k} of {} names vertex {i}, but there are {} vertices",
                    b.name,
                    b.vertices.len()
                )
            })?;
        }
        shapes.push(match outline(&corners) {
            Some(o) => pieces(o, facet.longitude_deg),
            None => Vec::new(),
        });
    }
    Ok(shapes)
}

/// `d` wrapped into [-180, 180), deg.
fn wrap180(d: f64) -> f64 {
    (d + 180.0).rem_euclid(360.0) - 180.0
}

/// The outline of a triangle on the map, its longitudes unwrapped from its first vertex's
/// (so that they run continuously, past +-180 where it crosses the seam); `None` if a
/// coordinate is not finite or two of its vertices lie on the spin axis.
fn outline(corners: &[[f64; 3]; 3]) -> Option<Vec<LonLat>> {
    // Longitude (None on the spin axis) and latitude of each vertex.
    let mut at = [(None, 0.0); 3];
    for (a, v) in at.iter_mut().zip(corners) {
        let [x, y, z] = *v;
        let (h, r) = (x.hypot(y), (x * x + y * y + z * z).sqrt());
        if !(r.is_finite() && r > 0.0) {
            return None;
        }
        let lat = z.atan2(h).to_degrees();
        *a = ((h > 1e-9 * r).then(|| y.atan2(x).to_degrees()), lat);
    }
    let on_axis = at.iter().filter(|a| a.0.is_none()).count();
    if on_axis > 1 {
        return None;
    }
    // Unwrapped longitudes of the vertices off the axis, in the triangle's order.
    let first = at.iter().position(|a| a.0.is_some())?;
    let mut lon = [f64::NAN; 3];
    let (mut prev, mut acc) = (at[first].0?, at[first].0?);
    for j in 0..3 {
        let i = (first + j) % 3;
        if let Some(l) = at[i].0 {
            acc += wrap180(l - prev);
            prev = l;
            lon[i] = acc;
        }
    }
    let pole = |lat: f64| if lat >= 0.0 { 90.0 } else { -90.0 };
    let mut out = Vec::with_capacity(5);
    if on_axis == 1 {
        // The vertex on the axis is the pole's edge of the map, from the longitude of the
        // vertex before it to that of the vertex after it.
        for i in 0..3 {
            match at[i].0 {
                Some(_) => out.push((lon[i], at[i].1)),
                None => {
                    let (before, after) = (lon[(i + 2) % 3], lon[(i + 1) % 3]);
                    out.push((before, pole(at[i].1)));
                    out.push((after, pole(at[i].1)));
                }
            }
        }
        return Some(out);
    }
    // The longitude the outline turns through, back to its first vertex: 0, or a whole
    // turn around a pole.
    let turn = acc - lon[first] + wrap180(at[first].0? - prev);
    out.extend((0..3).map(|i| (lon[i], at[i].1)));
    if turn.abs() > 180.0 {
        // The triangle rings the pole on its centroid's side: the band from its edges to
        // the map's edge, all the way round.
        let lat = pole(corners.iter().map(|c| c[2]).sum::<f64>());
        out.push((lon[0] + turn, at[0].1));
        out.push((lon[0] + turn, lat));
        out.push((lon[0], lat));
    }
    Some(out)
}

/// An unwrapped outline shifted by a whole turn to its facet's longitude `centre_deg` (or,
/// if that is not finite, to the map), and its copies a turn either side, each cut at the
/// frame; those that show.
fn pieces(mut outline: Vec<LonLat>, centre_deg: f64) -> Vec<Vec<LonLat>> {
    let n = outline.len() as f64;
    let mean = outline.iter().map(|p| p.0).sum::<f64>() / n;
    let target = if centre_deg.is_finite() {
        centre_deg
    } else {
        wrap180(mean)
    };
    let shift = 360.0 * ((target - mean) / 360.0).round();
    outline.iter_mut().for_each(|p| p.0 += shift);
    [-360.0, 0.0, 360.0]
        .iter()
        .filter_map(|d| {
            let moved: Vec<LonLat> = outline.iter().map(|p| (p.0 + d, p.1)).collect();
            let cut = clip_x(&clip_x(&moved, -180.0, true), 180.0, false);
            (cut.len() >= 3).then_some(cut)
        })
        .collect()
}

/// `poly` cut at the line x = `edge`, keeping the side x >= `edge` (`keep_above`) or x <=
/// `edge` (Sutherland and Hodgman's step for one edge).
fn clip_x(poly: &[LonLat], edge: f64, keep_above: bool) -> Vec<LonLat> {
    let inside = |p: &LonLat| if keep_above { p.0 >= edge } else { p.0 <= edge };
    let mut out = Vec::with_capacity(poly.len() + 2);
    for (k, p) in poly.iter().enumerate() {
        let q = &poly[(k + 1) % poly.len()];
        if inside(p) {
            out.push(*p);
        }
        if inside(p) != inside(q) {
            let t = (edge - p.0) / (q.0 - p.0);
            out.push((edge, p.1 + t * (q.1 - p.1)));
        }
    }
    out
}

/// One map: the facets' pieces in their colours, the frame, the axes.
fn draw_map(
    area: &Area<'_>,
    caption: &str,
    shapes: &[Vec<Vec<LonLat>>],
    colours: &[[u8; 3]],
) -> anyhow::Result<()> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 18))
        .margin(12)
        .margin_right(4)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(-180.0..180.0, -90.0..90.0)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(0)
        .y_labels(0)
        .x_desc("longitude (deg)")
        .y_desc("latitude (deg)")
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(drawing)?;
    ticks(area, &chart)?;
    for (pieces, c) in shapes.iter().zip(colours) {
        let colour = RGBColor(c[0], c[1], c[2]);
        for p in pieces {
            // Filled, and outlined in the same colour: neighbours meet without a hairline
            // of background between them.
            chart
                .draw_series([
                    Polygon::new(p.clone(), colour.filled()),
                    Polygon::new(p.clone(), colour.stroke_width(1)),
                ])
                .map_err(drawing)?;
        }
    }
    chart
        .draw_series([Rectangle::new([(-180.0, -90.0), (180.0, 90.0)], BLACK)])
        .map_err(drawing)?;
    Ok(())
}

/// The map's ticks and their labels: every 60 deg of longitude, every 30 of latitude.
fn ticks(area: &Area<'_>, chart: &Chart2d<'_, '_>) -> anyhow::Result<()> {
    let (x0, y0) = area.get_base_pixel();
    let at = |lon: f64, lat: f64| {
        let (x, y) = chart.backend_coord(&(lon, lat));
        (x - x0, y - y0)
    };
    let style = (FONT, 14).into_font().color(&BLACK);
    for k in -3..=3 {
        let lon = 60.0 * f64::from(k);
        let (x, y) = at(lon, -90.0);
        area.draw(&PathElement::new(vec![(x, y), (x, y + 5)], BLACK))
            .map_err(drawing)?;
        let centred = style.pos(Pos::new(HPos::Center, VPos::Top));
        area.draw(&Text::new(format!("{lon:.0}"), (x, y + 8), centred))
            .map_err(drawing)?;
        let lat = 30.0 * f64::from(k);
        let (x, y) = at(-180.0, lat);
        area.draw(&PathElement::new(vec![(x - 5, y), (x, y)], BLACK))
            .map_err(drawing)?;
        let right = style.pos(Pos::new(HPos::Right, VPos::Center));
        area.draw(&Text::new(format!("{lat:.0}"), (x - 8, y), right))
            .map_err(drawing)?;
    }
    Ok(())
}

/// A vertical colour bar from 0 to `top` with `colour` of each value, its ticks and
/// labels; with `swatches`, the landing sites' and the facets without shares' colours
/// below it, named.
fn colour_bar(
    area: &Area<'_>,
    caption: &str,
    top: f64,
    colour: &dyn Fn(f64) -> [u8; 3],
    swatches: bool,
) -> anyhow::Result<()> {
    let (bar, legend) = area.split_vertically(SIZE.1 - TITLE - 150);
    let mut chart = ChartBuilder::on(&bar)
        .caption(caption, (FONT, 15))
        .margin_top(26)
        .margin_bottom(14)
        .margin_left(14)
        .margin_right(40)
        .y_label_area_size(44)
        .build_cartesian_2d(0.0..1.0, 0.0..top)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(11)
        .y_label_formatter(&|v| {
            if top <= 1.0 {
                format!("{v:.1}")
            } else {
                format!("{v:.0}")
            }
        })
        .label_style((FONT, 13))
        .draw()
        .map_err(drawing)?;
    let steps = 300;
    chart
        .draw_series((0..steps).map(|k| {
            let (a, b) = (
                f64::from(k) / f64::from(steps),
                f64::from(k + 1) / f64::from(steps),
            );
            let c = colour(0.5 * (a + b) * top);
            Rectangle::new(
                [(0.0, a * top), (1.0, b * top)],
                RGBColor(c[0], c[1], c[2]).filled(),
            )
        }))
        .map_err(drawing)?;
    if !swatches {
        return Ok(());
    }
    let style = (FONT, 14).into_font();
    let entries = [
        (SAFE, format!("≥ {SAFE_P_STABLE}: site")),
        (NO_SHARES, "no shares".to_string()),
    ];
    for (k, (c, label)) in entries.into_iter().enumerate() {
        let y = 8 + 26 * k as i32;
        legend
            .draw(&Rectangle::new(
                [(14, y), (38, y + 18)],
                RGBColor(c[0], c[1], c[2]).filled(),
            ))
            .map_err(drawing)?;
        legend
            .draw(&Text::new(label, (46, y + 1), style.clone()))
            .map_err(drawing)?;
    }
    Ok(())
}
