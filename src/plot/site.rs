//! The picture of `touchdown site`: two maps of the body side by side in Mollweide's
//! equal-area projection of longitude and latitude about the spin axis, so that a region
//! takes the share of the map that it takes of the directions from the body's centre (of
//! a sphere's surface): a polar cap is not widened into a band. Left, P(stable) on a
//! perceptual scale with the landing sites (`SiteFacet::safe`) in a colour of their own,
//! and the facets without shares in two more (no samples; too steep); right, the slope on
//! a scale of 0 to 90 deg for every body. The colour scales are public: the 3D page
//! (`crate::view::site`) colours the body with the same ones.
//!
//! Each facet is drawn as its true outline: its edges, straight in space, followed in
//! longitude and latitude point by point until the outline bends by less than
//! `OUTLINE_TOLERANCE_DEG` between points, then projected. A triangle that crosses the
//! +-180 deg seam is drawn on both sides of the map, each copy cut at the seam; a triangle
//! with a vertex on the spin axis reaches the pole along the longitudes of its other two
//! vertices, and one around a pole covers the map around it.

use super::canvas::{Area, Chart2d, FONT, drawing, save_png};
use crate::site::{SAFE_P_STABLE, Site, SiteFacet};
use anyhow::bail;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// The picture's size, pixels: two maps of 2:1 side by side, their colour bars, a title.
const SIZE: (u32, u32) = (1800, 560);
/// Height of the title strip, pixels.
const TITLE: u32 = 46;
/// Width of each map's colour-bar strip, pixels.
const BAR: u32 = 150;

/// The colour of the maps' text (not pure black, which only the maps' edges are drawn in).
const TEXT: RGBColor = RGBColor(40, 40, 40);

/// How far a facet's outline may bend between two of its drawn points, deg (longitude
/// scaled by the cosine of the latitude).
const OUTLINE_TOLERANCE_DEG: f64 = 0.2;

/// The longest step along the map's seam or a pole's edge before it is projected, deg.
const STEP_DEG: f64 = 2.0;

/// The colour of facets too steep to stand on (and of values that are not finite).
pub const NO_SHARES: [u8; 3] = [170, 170, 170];

/// The colour of facets a lander could stand on whose window held no sample: what the map
/// does not know (a sky blue, a hue neither scale takes).
pub const NO_SAMPLES: [u8; 3] = [86, 180, 233];

/// The colour of landing sites: facets whose P(stable) is at least `SAFE_P_STABLE` with
/// 95 % confidence (`SiteFacet::safe`; a bluish green, a hue the P(stable) scale never
/// takes).
pub const SAFE: [u8; 3] = [0, 158, 115];

/// The top of the slope scale, deg, the same for every body so that maps compare: a
/// steeper facet (the effective gravity off the ground) takes its top colour, and the
/// legend says so.
pub const SLOPE_TOP_DEG: f64 = 90.0;

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

/// The colour of a P(stable) on its scale, `NO_SHARES` without one or when it is not
/// finite.
#[must_use]
pub fn p_stable_colour(p: Option<f64>) -> [u8; 3] {
    p.map_or(NO_SHARES, |p| scale_colour(&P_STABLE_SCALE, p))
}

/// The colour of a facet on the P(stable) map: `SAFE` for a landing site, else its
/// P(stable) on the scale; without shares `NO_SAMPLES` where a lander could stand (its
/// window held no sample) and `NO_SHARES` where it is too steep.
#[must_use]
pub fn facet_colour(f: &SiteFacet) -> [u8; 3] {
    match f.p_stable() {
        _ if f.safe() => SAFE,
        Some(s) => p_stable_colour(Some(s.p)),
        None if f.standing() => NO_SAMPLES,
        None => NO_SHARES,
    }
}

/// The colour of a slope on its scale, 0 to `SLOPE_TOP_DEG` (steeper takes the top).
#[must_use]
pub fn slope_colour(slope_deg: f64) -> [u8; 3] {
    scale_colour(&SLOPE_SCALE, slope_deg / SLOPE_TOP_DEG)
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
    let p_colours: Vec<[u8; 3]> = site.facets.iter().map(facet_colour).collect();
    let slope_colours: Vec<[u8; 3]> = site
        .facets
        .iter()
        .map(|f| slope_colour(f.slope_deg))
        .collect();
    let steepest = site
        .facets
        .iter()
        .map(|f| f.slope_deg)
        .filter(|s| s.is_finite())
        .fold(0.0f64, f64::max);
    let b = &site.body;
    let title = format!(
        "Landing sites on {}: density {} kg/m³, spin period {} h, {} facets",
        b.name,
        short(b.density_kg_m3),
        short(b.spin_period_h),
        site.facets.len()
    );
    let safe = format!(
        "P(stable) ≥ {SAFE_P_STABLE} with 95 % confidence on {:.1} % of the surface \
         (point estimate: {:.1} %)",
        100.0 * site.safe_area_fraction(),
        100.0 * site.safe_area_fraction_point_estimate()
    );
    let mean = mean_slope_deg(site).map_or("no slopes".into(), |m| {
        format!("area-weighted mean {m:.1}°")
    });
    save_png(path, SIZE, |root| {
        let (head, rest) = root.split_vertically(TITLE);
        head.titled(&title, (FONT, 22).into_font().color(&TEXT))
            .map_err(drawing)?;
        let halves = rest.split_evenly((1, 2));
        let (map, bar) = halves[0].split_horizontally(SIZE.0 / 2 - BAR);
        draw_map(&map, &safe, &shapes, &p_colours)?;
        let swatches = [
            (SAFE, format!("site: low end ≥ {SAFE_P_STABLE}")),
            (NO_SAMPLES, "no samples".to_string()),
            (NO_SHARES, "too steep".to_string()),
        ];
        colour_bar(
            &bar,
            "P(stable)",
            1.0,
            &|t| p_stable_colour(Some(t)),
            &swatches,
        )?;
        let (map, bar) = halves[1].split_horizontally(SIZE.0 / 2 - BAR);
        draw_map(
            &map,
            &format!("slope (deg), {mean}"),
            &shapes,
            &slope_colours,
        )?;
        // Steeper than the scale's top: drawn in its colour, and said so.
        let steep = if steepest > SLOPE_TOP_DEG {
            vec![(
                slope_colour(SLOPE_TOP_DEG),
                format!("{SLOPE_TOP_DEG:.0}-{steepest:.0}°: as {SLOPE_TOP_DEG:.0}"),
            )]
        } else {
            Vec::new()
        };
        colour_bar(&bar, "slope (deg)", SLOPE_TOP_DEG, &slope_colour, &steep)
    })
}

/// A number for a title: up to 4 significant digits, no trailing zeros.
fn short(v: f64) -> String {
    if !v.is_finite() || v == 0.0 || v.abs() >= 1e16 {
        return crate::site::given_number(v);
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

/// A piece of a facet on the map, projected: a polygon in the map's plane.
type Piece = Vec<(f64, f64)>;

/// Half the width and half the height of Mollweide's map, in its own units.
const HALF_WIDTH: f64 = 2.0 * std::f64::consts::SQRT_2;
const HALF_HEIGHT: f64 = std::f64::consts::SQRT_2;

/// Mollweide's equal-area projection of longitude `lon_deg` (in [-180, 180]) and latitude
/// `lat_deg`: `x = (2 sqrt 2 / pi) lon cos t`, `y = sqrt 2 sin t`, with `2 t + sin 2t = pi
/// sin(lat)`; the map is the ellipse of half-axes `2 sqrt 2` and `sqrt 2`, and the share of
/// its area a region takes is the share of the sphere's.
#[must_use]
pub fn mollweide(lon_deg: f64, lat_deg: f64) -> (f64, f64) {
    let (lon, lat) = (
        lon_deg.to_radians(),
        lat_deg.clamp(-90.0, 90.0).to_radians(),
    );
    let target = std::f64::consts::PI * lat.sin();
    // Newton on u = 2t: u + sin u = target, from u = 2 lat (exact at the equator); at the
    // poles the root is double and Newton slow, so the iterations stop at a tolerance.
    let mut u = 2.0 * lat;
    for _ in 0..60 {
        let step = (u + u.sin() - target) / (1.0 + u.cos()).max(1e-12);
        u -= step;
        if step.abs() < 1e-13 {
            break;
        }
    }
    let t = (0.5 * u).clamp(-std::f64::consts::FRAC_PI_2, std::f64::consts::FRAC_PI_2);
    (
        HALF_WIDTH / std::f64::consts::PI * lon * t.cos(),
        HALF_HEIGHT * t.sin(),
    )
}

/// Each facet's pieces on the map, projected: its true outline (a band round a pole where
/// it rings one), cut at the seam and drawn once more on the other side where it crosses
/// it. Vertices are taken in the spin's frame (`shape::spin_frame`), as the facets'
/// latitudes and longitudes are.
fn map_shapes(site: &Site) -> anyhow::Result<Vec<Vec<Piece>>> {
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
    let frame = crate::shape::spin_frame(b.spin_axis);
    let in_frame = |v: [f64; 3]| {
        if b.spin_axis == [0.0, 0.0, 1.0] {
            v
        } else {
            frame.map(|e| e[0] * v[0] + e[1] * v[1] + e[2] * v[2])
        }
    };
    let mut shapes = Vec::with_capacity(site.facets.len());
    for (k, (facet, t)) in site.facets.iter().zip(&b.triangles).enumerate() {
        let mut corners = [[0.0; 3]; 3];
        for (c, &i) in corners.iter_mut().zip(t) {
            *c = in_frame(*b.vertices.get(i as usize).ok_or_else(|| {
                anyhow::anyhow!(
                    "triangle {k} of {} names vertex {i}, but there are {} vertices",
                    b.name,
                    b.vertices.len()
                )
            })?);
        }
        shapes.push(match outline(&corners) {
            Some(o) => pieces(o, facet.longitude_deg)
                .iter()
                .map(|p| projected(p))
                .collect(),
            None => Vec::new(),
        });
    }
    Ok(shapes)
}

/// `d` wrapped into [-180, 180), deg.
fn wrap180(d: f64) -> f64 {
    (d + 180.0).rem_euclid(360.0) - 180.0
}

/// A point's longitude (`None` on the spin axis) and latitude, deg; `None` if it is not
/// finite or at the origin.
fn lon_lat(v: [f64; 3]) -> Option<(Option<f64>, f64)> {
    let [x, y, z] = v;
    let (h, r) = (x.hypot(y), (x * x + y * y + z * z).sqrt());
    if !(r.is_finite() && r > 0.0) {
        return None;
    }
    Some((
        (h > 1e-9 * r).then(|| y.atan2(x).to_degrees()),
        z.atan2(h).to_degrees(),
    ))
}

/// The points strictly between `a` and `b` along the straight edge from `a` to `b`, in
/// order, as many as the outline needs to bend by less than `OUTLINE_TOLERANCE_DEG` between
/// them (`depth` halvings at most).
fn edge_points(a: [f64; 3], b: [f64; 3], depth: u32, out: &mut Vec<(Option<f64>, f64)>) {
    let m = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
    let (Some(pa), Some(pb), Some(pm)) = (lon_lat(a), lon_lat(b), lon_lat(m)) else {
        return;
    };
    // An end on the axis: the edge runs along its other end's meridian.
    let (Some(la), Some(lb), Some(lm)) = (pa.0, pb.0, pm.0) else {
        return;
    };
    let lon_mid = la + 0.5 * wrap180(lb - la);
    let bend = (wrap180(lm - lon_mid) * pm.1.to_radians().cos()).hypot(pm.1 - 0.5 * (pa.1 + pb.1));
    if depth == 0 || bend < OUTLINE_TOLERANCE_DEG {
        return;
    }
    edge_points(a, m, depth - 1, out);
    out.push(pm);
    edge_points(m, b, depth - 1, out);
}

/// The true outline of a triangle on the map, its longitudes unwrapped from its first
/// point's (so that they run continuously, past +-180 where it crosses the seam); `None`
/// if a coordinate is not finite or two of its vertices lie on the spin axis.
fn outline(corners: &[[f64; 3]; 3]) -> Option<Vec<LonLat>> {
    // Longitude (None on the spin axis) and latitude of each point of the outline, and
    // whether it is a vertex on the axis.
    let mut ring: Vec<(Option<f64>, f64)> = Vec::with_capacity(24);
    for k in 0..3 {
        ring.push(lon_lat(corners[k])?);
        edge_points(corners[k], corners[(k + 1) % 3], 12, &mut ring);
    }
    let on_axis = ring.iter().filter(|a| a.0.is_none()).count();
    if on_axis > 1 {
        return None;
    }
    // Unwrapped longitudes of the points off the axis, in order.
    let n = ring.len();
    let first = ring.iter().position(|a| a.0.is_some())?;
    let mut lon = vec![f64::NAN; n];
    let (mut prev, mut acc) = (ring[first].0?, ring[first].0?);
    for j in 0..n {
        let i = (first + j) % n;
        if let Some(l) = ring[i].0 {
            acc += wrap180(l - prev);
            prev = l;
            lon[i] = acc;
        }
    }
    let pole = |lat: f64| if lat >= 0.0 { 90.0 } else { -90.0 };
    let mut out = Vec::with_capacity(n + 3);
    if on_axis == 1 {
        // The vertex on the axis is the pole, reached from the longitude of the point
        // before it and left at that of the point after it.
        for i in 0..n {
            match ring[i].0 {
                Some(_) => out.push((lon[i], ring[i].1)),
                None => {
                    let (before, after) = (lon[(i + n - 1) % n], lon[(i + 1) % n]);
                    out.push((before, pole(ring[i].1)));
                    out.push((after, pole(ring[i].1)));
                }
            }
        }
        return Some(out);
    }
    // The longitude the outline turns through, back to its first point: 0, or a whole
    // turn around a pole.
    let turn = acc - lon[first] + wrap180(ring[first].0? - prev);
    out.extend((0..n).map(|i| (lon[i], ring[i].1)));
    if turn.abs() > 180.0 {
        // The triangle rings the pole on its centroid's side: the band from its edges to
        // the pole, all the way round.
        let lat = pole(corners.iter().map(|c| c[2]).sum::<f64>());
        out.push((lon[0] + turn, ring[0].1));
        out.push((lon[0] + turn, lat));
        out.push((lon[0], lat));
    }
    Some(out)
}

/// An unwrapped outline shifted by a whole turn to its facet's longitude `centre_deg` (or,
/// if that is not finite, to the map), and its copies a turn either side, each cut at the
/// seam; those that show.
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

/// A piece of the map in (longitude, latitude), projected: its sides along the seam or a
/// pole's edge (straight in longitude and latitude, curved on the map) in steps of
/// `STEP_DEG` first.
fn projected(piece: &[LonLat]) -> Piece {
    let mut out = Vec::with_capacity(piece.len() + 8);
    for (k, &(lon, lat)) in piece.iter().enumerate() {
        let (lon2, lat2) = piece[(k + 1) % piece.len()];
        let steps = ((lon2 - lon).abs().max((lat2 - lat).abs()) / STEP_DEG)
            .ceil()
            .clamp(1.0, 360.0) as usize;
        for j in 0..steps {
            let t = j as f64 / steps as f64;
            out.push(mollweide(lon + t * (lon2 - lon), lat + t * (lat2 - lat)));
        }
    }
    out
}

/// One map: the facets' pieces in their colours, the graticule, the map's edge and its
/// labels. The map keeps its 2:1 shape in the middle of `area`.
fn draw_map(
    area: &Area<'_>,
    caption: &str,
    shapes: &[Vec<Piece>],
    colours: &[[u8; 3]],
) -> anyhow::Result<()> {
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (i32::try_from(w)?, i32::try_from(h)?);
    // Room for the caption above, the longitudes below and the latitudes on the left.
    let (top, bottom, left, right) = (36, 30, 44, 12);
    let width = (w - left - right).min(2 * (h - top - bottom)).max(2);
    let height = width / 2;
    let x0 = left + (w - left - right - width) / 2;
    let y0 = top + (h - top - bottom - height) / 2;
    let mut chart = ChartBuilder::on(area)
        .margin_left(x0)
        .margin_right(w - x0 - width)
        .margin_top(y0)
        .margin_bottom(h - y0 - height)
        .build_cartesian_2d(-HALF_WIDTH..HALF_WIDTH, -HALF_HEIGHT..HALF_HEIGHT)
        .map_err(drawing)?;
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
    // The graticule, faint: meridians every 60 deg, parallels every 30.
    let faint = BLACK.mix(0.18);
    let line = |points: Vec<LonLat>| {
        PathElement::new(
            points
                .into_iter()
                .map(|(lon, lat)| mollweide(lon, lat))
                .collect::<Vec<_>>(),
            faint,
        )
    };
    let along =
        |from: f64, to: f64| (0..=90).map(move |j| from + (to - from) * f64::from(j) / 90.0);
    for k in -2..=2 {
        let lon = 60.0 * f64::from(k);
        chart
            .draw_series([line(along(-90.0, 90.0).map(|lat| (lon, lat)).collect())])
            .map_err(drawing)?;
        let lat = 30.0 * f64::from(k);
        chart
            .draw_series([line(along(-180.0, 180.0).map(|lon| (lon, lat)).collect())])
            .map_err(drawing)?;
    }
    // The map's edge, the +-180 deg meridian: pure black, drawn in nothing else.
    let edge: Vec<(f64, f64)> = along(-90.0, 90.0)
        .map(|lat| mollweide(180.0, lat))
        .chain(along(90.0, -90.0).map(|lat| mollweide(-180.0, lat)))
        .collect();
    chart
        .draw_series([PathElement::new(
            edge.iter()
                .copied()
                .chain(edge.first().copied())
                .collect::<Vec<_>>(),
            BLACK,
        )])
        .map_err(drawing)?;
    labels(area, &chart, caption)
}

/// The map's caption and labels: longitudes every 60 deg below the map, where their
/// meridians cross the equator; latitudes every 30 deg at the map's edge.
fn labels(area: &Area<'_>, chart: &Chart2d<'_, '_>, caption: &str) -> anyhow::Result<()> {
    let (x0, y0) = area.get_base_pixel();
    let at = |lon: f64, lat: f64| {
        let (x, y) = chart.backend_coord(&mollweide(lon, lat));
        (x - x0, y - y0)
    };
    let style = (FONT, 14).into_font().color(&TEXT);
    let (_, bottom) = at(0.0, -90.0);
    let (_, top) = at(0.0, 90.0);
    let (left, _) = at(-180.0, 0.0);
    let (right, _) = at(180.0, 0.0);
    area.draw(&Text::new(
        caption.to_string(),
        ((left + right) / 2, top - 12),
        (FONT, 18)
            .into_font()
            .color(&TEXT)
            .pos(Pos::new(HPos::Center, VPos::Bottom)),
    ))
    .map_err(drawing)?;
    for k in -3..=3 {
        let lon = 60.0 * f64::from(k);
        let (x, _) = at(lon, 0.0);
        let centred = style.pos(Pos::new(HPos::Center, VPos::Top));
        area.draw(&Text::new(format!("{lon:.0}"), (x, bottom + 6), centred))
            .map_err(drawing)?;
        let lat = 30.0 * f64::from(k);
        if lat.abs() == 90.0 {
            // The poles are points, at the map's top and bottom.
            continue;
        }
        let (x, y) = at(-180.0, lat);
        let right_aligned = style.pos(Pos::new(HPos::Right, VPos::Center));
        area.draw(&Text::new(format!("{lat:.0}"), (x - 6, y), right_aligned))
            .map_err(drawing)?;
    }
    Ok(())
}

/// A vertical colour bar from 0 to `top` with `colour` of each value, its ticks and
/// labels, and below it `swatches`, colours named.
fn colour_bar(
    area: &Area<'_>,
    caption: &str,
    top: f64,
    colour: &dyn Fn(f64) -> [u8; 3],
    swatches: &[([u8; 3], String)],
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
    let style = (FONT, 14).into_font();
    for (k, (c, label)) in swatches.iter().enumerate() {
        let y = 8 + 26 * k as i32;
        legend
            .draw(&Rectangle::new(
                [(14, y), (38, y + 18)],
                RGBColor(c[0], c[1], c[2]).filled(),
            ))
            .map_err(drawing)?;
        legend
            .draw(&Text::new(label.as_str(), (46, y + 1), style.clone()))
            .map_err(drawing)?;
    }
    Ok(())
}
