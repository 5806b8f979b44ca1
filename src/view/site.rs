//! The 3D page of `touchdown site`: one self-contained HTML page of the body, drawn on a
//! canvas by its own painter's-algorithm renderer (orbit by dragging, zoom by the wheel),
//! coloured by P(stable), the slope or the gravity on the scales of the map picture
//! (`crate::plot::site`), with a facet's numbers under the pointer.
//!
//! The page is `site.html` with the site spliced in as JSON: nothing is fetched, so it opens
//! from a mail attachment or a folder with no network. The numbers are rounded to what the
//! page shows or draws (6 significant digits for coordinates, 4 for shares, slopes,
//! roughness and gravity), which keeps the page of a 12,000-facet body near 1.4 MB.

use super::text;
use crate::output::{AtomicFile, cannot_write};
use crate::plot::site::{NO_SAMPLES, NO_SHARES, P_STABLE_SCALE, SAFE, SLOPE_SCALE, SLOPE_TOP_DEG};
use crate::site::{SAFE_P_STABLE, SLOPE_LIMIT_DEG, Site, SiteFacet};
use anyhow::bail;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// The page, with `PLACEHOLDER` where the site goes.
const TEMPLATE: &str = include_str!("site.html");
const PLACEHOLDER: &str = "\"__TOUCHDOWN_SITE_JSON__\"";

/// Significant digits of the page's coordinates, and of its other numbers.
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
    let json = site_json(site);
    // `</` would end the script element that holds the JSON; `<\/` reads the same in JSON.
    let page = TEMPLATE.replacen(PLACEHOLDER, &json.replace("</", "<\\/"), 1);
    let (file, mut sink) = AtomicFile::create(path)?;
    sink.write_all(page.as_bytes())
        .and_then(|()| sink.flush())
        .map_err(|e| cannot_write(path, e))?;
    file.commit(sink)
}

/// The site as the page reads it: the body and its numbers, the colour scales, the
/// vertices and triangles (flat), and each facet's numbers as columns (`null` where a
/// number is missing or not finite).
fn site_json(site: &Site) -> String {
    let b = &site.body;
    let mut o = String::with_capacity(128 * site.facets.len() + 1024);
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
    o.push_str("},\"vertices\":");
    list(
        &mut o,
        b.vertices.iter().flatten().copied(),
        COORDINATE_DIGITS,
    );
    o.push_str(",\"triangles\":[");
    for (k, i) in b.triangles.iter().flatten().enumerate() {
        if k > 0 {
            o.push(',');
        }
        let _ = write!(o, "{i}");
    }
    o.push_str("],\"facets\":");
    facets(&mut o, &site.facets);
    o.push('}');
    o
}

/// A number of a facet, a column of the page.
type Column = fn(&SiteFacet) -> f64;

/// The facets' numbers, a column each (in the order of `SHARE_OUTCOMES` for the shares).
fn facets(o: &mut String, facets: &[SiteFacet]) {
    o.push_str("{\"facet\":[");
    for (k, f) in facets.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        let _ = write!(o, "{}", f.facet);
    }
    o.push_str("],\"samples\":[");
    for (k, f) in facets.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        let _ = write!(o, "{}", f.samples);
    }
    // Whether each is a landing site, decided here on the unrounded interval.
    o.push_str("],\"safe\":[");
    for (k, f) in facets.iter().enumerate() {
        if k > 0 {
            o.push(',');
        }
        o.push(if f.safe() { '1' } else { '0' });
    }
    o.push(']');
    // The numbers, then the shares: P(stable) with its interval, the other outcomes' P.
    let columns: [(&str, Column); 11] = [
        ("latitude_deg", |f| f.latitude_deg),
        ("longitude_deg", |f| f.longitude_deg),
        ("slope_deg", |f| f.slope_deg),
        ("roughness_deg", |f| f.roughness_deg),
        ("gravity_m_s2", |f| f.gravity_m_s2),
        ("stable", |f| f.shares.map_or(f64::NAN, |s| s[0].p)),
        ("stable_low", |f| f.shares.map_or(f64::NAN, |s| s[0].low)),
        ("stable_high", |f| f.shares.map_or(f64::NAN, |s| s[0].high)),
        ("tipped", |f| f.shares.map_or(f64::NAN, |s| s[1].p)),
        ("sliding", |f| f.shares.map_or(f64::NAN, |s| s[2].p)),
        ("bouncing", |f| f.shares.map_or(f64::NAN, |s| s[3].p)),
    ];
    for (name, value) in columns {
        let _ = write!(o, ",\"{name}\":");
        list(o, facets.iter().map(value), DIGITS);
    }
    o.push('}');
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

/// Numbers as a JSON array.
fn list(o: &mut String, values: impl Iterator<Item = f64>, digits: usize) {
    o.push('[');
    for (k, v) in values.enumerate() {
        if k > 0 {
            o.push(',');
        }
        num(o, v, digits);
    }
    o.push(']');
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
