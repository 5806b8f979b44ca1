//! The 3D page of `touchdown site`: one self-contained HTML page of the body, drawn with
//! WebGL 2 (every facet, a depth buffer; orbit by dragging, zoom by the wheel), coloured by
//! P(stable), the slope or the gravity on the scales of the map picture
//! (`crate::plot::site`), with the numbers of the facet under the pointer (found by drawing
//! each facet's number into a picture of its own and reading the pixel there).
//!
//! The page is `site.html` with the site spliced in: a JSON header (the body, the scales)
//! and the vertices, triangles and facets' numbers packed (`super::packed`: quantized to
//! the steps below, differenced, deflated, base64). Nothing is fetched, so it opens from a
//! mail attachment or a folder with no network. A body of 1.3 million facets makes a page
//! of 13.4 MB that headless Chromium opened and drew in 3.2-3.9 s; one of 12,192, 45 kB.

use super::packed::{MISSING, Packed, Scale};
use super::text;
use crate::output::{AtomicFile, cannot_write};
use crate::plot::site::{NO_SAMPLES, NO_SHARES, P_STABLE_SCALE, SAFE, SLOPE_SCALE, SLOPE_TOP_DEG};
use crate::site::{SAFE_P_STABLE, SLOPE_LIMIT_DEG, Site};
use anyhow::bail;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// The page, with `PLACEHOLDER` where the site goes.
const TEMPLATE: &str = include_str!("site.html");
const PLACEHOLDER: &str = "\"__TOUCHDOWN_SITE_JSON__\"";

/// Significant digits of the body's numbers in the header (mass, area, ...), and of the scales'.
const COORDINATE_DIGITS: usize = 6;
const DIGITS: usize = 4;

/// Writes the 3D page of `site` to `path` (HTML). Refuses a site without facets or with as
/// many triangles as facets missing.
pub fn site_page(site: &Site, path: &Path) -> anyhow::Result<()> {
    crate::output::check_output_path(path)?;
    let b = &site.body;
    if site.facets.is_empty() {
        bail!("the landing-site page of {} has no facets to show", b.name);
    }
    if b.triangles.len() != site.facets.len() {
        bail!(
            "the landing-site page of {} has {} facets but {} triangles",
            b.name,
            site.facets.len(),
            b.triangles.len()
        );
    }
    let json = site_json(site)?;
    // `</` would end the script element that holds the JSON; `<\/` reads the same in JSON.
    let page = TEMPLATE.replacen(PLACEHOLDER, &json.replace("</", "<\\/"), 1);
    let (file, mut sink) = AtomicFile::create(path)?;
    sink.write_all(page.as_bytes())
        .and_then(|()| sink.flush())
        .map_err(|e| cannot_write(path, e))?;
    file.commit(sink)
}

/// Vertex coordinates are kept to this share of the body's largest extent (16 bits): 9 mm
/// on a body 600 m across, far below a pixel of any view of it.
const COORDINATE_STEPS: f64 = 65_535.0;
/// Latitude and longitude are kept to 0.01 deg, slope and roughness to 0.001 deg, the
/// gravity to a relative 1.06e-5 (a step of 2^-16 in its log2), the shares to 1e-6.
const LAT_LON_STEP_DEG: f64 = 0.01;
const ANGLE_STEP_DEG: f64 = 0.001;
const GRAVITY_LOG2_STEP: f64 = 1.0 / 65_536.0;
const SHARE_STEP: f64 = 1e-6;

/// The site as the page reads it: the body and its numbers, the colour scales, then the
/// packed columns (`super::packed`): the vertices, the triangles and each facet's numbers,
/// and the table of the windows whose shares the facets show (the facets of one window, of
/// the same samples and shares, share a row).
fn site_json(site: &Site) -> anyhow::Result<String> {
    let b = &site.body;
    let mut o = String::with_capacity(1024);
    o.push_str("{\"body\":{\"name\":");
    text(&mut o, &b.name);
    for (key, v) in [
        ("density_kg_m3", b.density_kg_m3),
        ("spin_period_h", b.spin_period_h),
        ("mass_kg", b.mass_kg),
        ("volume_m3", b.volume_m3),
        ("area_m2", b.area_m2),
        ("safe_area_fraction", site.safe_area_fraction()),
        (
            "safe_area_fraction_point_estimate",
            site.safe_area_fraction_point_estimate(),
        ),
    ] {
        let _ = write!(o, ",\"{key}\":");
        num(&mut o, v, COORDINATE_DIGITS);
    }
    o.push_str("},\"scales\":{\"p_stable\":");
    colours(&mut o, &P_STABLE_SCALE);
    o.push_str(",\"slope\":");
    colours(&mut o, &SLOPE_SCALE);
    let ([r, g, bl], [r0, g0, b0], [r1, g1, b1]) = (SAFE, NO_SHARES, NO_SAMPLES);
    let _ = write!(
        o,
        ",\"safe\":[{r},{g},{bl}],\"none\":[{r0},{g0},{b0}],\"no_samples\":[{r1},{g1},{b1}]"
    );
    let _ = write!(o, ",\"safe_p_stable\":{SAFE_P_STABLE}");
    let _ = write!(o, ",\"slope_limit_deg\":{SLOPE_LIMIT_DEG}");
    o.push_str(",\"slope_top_deg\":");
    num(&mut o, SLOPE_TOP_DEG, DIGITS);
    let (windows, window_of) = windows(site)?;
    let _ = write!(
        o,
        "}},\"vertices\":{},\"facets\":{},\"windows\":{},",
        b.vertices.len(),
        site.facets.len(),
        windows.len()
    );
    let mut p = Packed::default();
    // The vertices, each coordinate from the bounding box's low corner.
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in &b.vertices {
        for a in 0..3 {
            lo[a] = lo[a].min(v[a]);
            hi[a] = hi[a].max(v[a]);
        }
    }
    let extent = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    if !extent.is_finite() {
        bail!(
            "the landing-site page of {}: a vertex is not finite",
            b.name
        );
    }
    let step = if extent > 0.0 {
        extent / COORDINATE_STEPS
    } else {
        1.0
    };
    for (a, name) in ["x", "y", "z"].into_iter().enumerate() {
        let scale = Scale::Linear {
            offset: lo[a],
            scale: step,
        };
        p.numbers(name, scale, b.vertices.iter().map(|v| v[a]));
    }
    // Vertex numbers as 32-bit integers: a mesh of 2^31 vertices is far beyond memory.
    let one = Scale::Linear {
        offset: 0.0,
        scale: 1.0,
    };
    let t = &b.triangles;
    p.column(
        "triangles",
        one,
        (0..3 * t.len()).map(|k| t[k / 3][k % 3] as i32),
    );
    let fs = &site.facets;
    // The facets' own numbers, unless they are 0, 1, 2, ... (as every map's are).
    if fs.iter().enumerate().any(|(k, f)| f.facet as usize != k) {
        p.column("facet", one, fs.iter().map(|f| f.facet as i32));
    }
    let lat_lon = Scale::Linear {
        offset: 0.0,
        scale: LAT_LON_STEP_DEG,
    };
    let angle = Scale::Linear {
        offset: 0.0,
        scale: ANGLE_STEP_DEG,
    };
    let gravity = Scale::Log2 {
        scale: GRAVITY_LOG2_STEP,
    };
    p.numbers("latitude_deg", lat_lon, fs.iter().map(|f| f.latitude_deg));
    p.numbers("longitude_deg", lat_lon, fs.iter().map(|f| f.longitude_deg));
    p.numbers("slope_deg", angle, fs.iter().map(|f| f.slope_deg));
    p.numbers("roughness_deg", angle, fs.iter().map(|f| f.roughness_deg));
    p.numbers("gravity_m_s2", gravity, fs.iter().map(|f| f.gravity_m_s2));
    p.column("window", one, window_of.into_iter());
    // The windows' table: samples, whether a landing site (decided on the unrounded
    // interval), then the shares.
    p.column("samples", one, windows.iter().map(|w| w.samples));
    p.column("safe", one, windows.iter().map(|w| i32::from(w.safe)));
    let share = Scale::Linear {
        offset: 0.0,
        scale: SHARE_STEP,
    };
    for (k, name) in SHARE_COLUMNS.into_iter().enumerate() {
        p.column(name, share, windows.iter().map(|w| w.shares[k]));
    }
    o.push_str(&p.finish()?);
    o.push('}');
    Ok(o)
}

/// The shares of a window's row, in this order.
const SHARE_COLUMNS: [&str; 6] = [
    "stable",
    "stable_low",
    "stable_high",
    "tipped",
    "sliding",
    "bouncing",
];

/// A row of the windows' table: what the facets of one window show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct WindowRow {
    samples: i32,
    safe: bool,
    /// The shares of `SHARE_COLUMNS` on the page's scale (`MISSING` where none).
    shares: [i32; 6],
}

/// The windows' table, in the order of the facets that first show each row, and each
/// facet's row.
fn windows(site: &Site) -> anyhow::Result<(Vec<WindowRow>, Vec<i32>)> {
    let share = Scale::Linear {
        offset: 0.0,
        scale: SHARE_STEP,
    };
    let mut rows = Vec::new();
    let mut index = HashMap::new();
    let mut of = Vec::with_capacity(site.facets.len());
    for f in &site.facets {
        let Ok(samples) = i32::try_from(f.samples) else {
            bail!(
                "the landing-site page of {}: a facet's window holds {} samples, more than \
                 the page keeps (2^31)",
                site.body.name,
                f.samples
            );
        };
        let shares = f.shares.map_or([MISSING; 6], |s| {
            [s[0].p, s[0].low, s[0].high, s[1].p, s[2].p, s[3].p].map(|v| share.quantize(v))
        });
        let row = WindowRow {
            samples,
            safe: f.safe(),
            shares,
        };
        let k = *index.entry(row).or_insert_with(|| {
            rows.push(row);
            rows.len() - 1
        });
        // No more rows than facets, and the facets' count fits an i32 as the corners' do.
        of.push(k as i32);
    }
    Ok((rows, of))
}

/// A number as JSON, rounded to `digits` significant digits; `null` when not finite.
fn num(o: &mut String, v: f64, digits: usize) {
    if !v.is_finite() {
        o.push_str("null");
        return;
    }
    // Rounded through its decimal exponent form, then written in the shortest form that
    // reads back the same: 0.9951, 123.457, 8.123e-5.
    let rounded: f64 = format!("{v:.*e}", digits.saturating_sub(1))
        .parse()
        .unwrap_or(v);
    let a = rounded.abs();
    if a != 0.0 && !(1e-4..1e15).contains(&a) {
        let _ = write!(o, "{rounded:e}");
    } else {
        let _ = write!(o, "{rounded}");
    }
}

/// Colours as a JSON array of [r, g, b] arrays.
fn colours(o: &mut String, stops: &[[u8; 3]]) {
    o.push('[');
    for (k, [r, g, b]) in stops.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        let _ = write!(o, "[{r},{g},{b}]");
    }
    o.push(']');
}
