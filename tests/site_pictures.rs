//! The pictures of a landing-site map (issue 34): the map picture draws each facet at its
//! longitude and latitude in the colour of its P(stable) and of its slope, crossing the
//! seam without smearing; the 3D page holds every facet's numbers, fetches nothing, and in
//! headless Chromium draws the body and names the facet under the pointer.
//!
//! The site is made up here: a UV sphere whose facets' numbers are functions of their
//! latitude band (and, in the seam's column, of their longitude), so the colour of every
//! place of the map is known. `TOUCHDOWN_SITE_PICTURES=DIR` copies the pictures into DIR.

use crate::common::TempDir;
use std::path::Path;
use touchdown::plot::site::{
    NO_SHARES, P_STABLE_SCALE, SAFE, SLOPE_SCALE, p_stable_colour, scale_colour, site_map,
};
use touchdown::site::{Body, FacetShare, Site, SiteFacet};

/// Longitudes and latitude bands of the test sphere: 24 x 12, 15 deg each, 528 facets.
const LONS: usize = 24;
const BANDS: usize = 12;
/// The sphere's vertices sit at longitudes 7.5 + 15 k, so that a column of facets
/// straddles the +-180 deg seam (vertices at 172.5 and -172.5 deg).
const LON0: f64 = 7.5;
const RADIUS_M: f64 = 200.0;

/// P(stable) of a facet in the band around latitude `band_deg` (its middle) with its
/// centroid at longitude `lon_deg`: no shares above 60 deg of latitude, a landing site
/// within 15 of the equator, 0 in the seam's column, else rising with latitude.
fn p_stable(band_deg: f64, lon_deg: f64) -> Option<f64> {
    match band_deg.abs() {
        a if a > 60.0 => None,
        a if a < 15.0 => Some(0.995),
        _ if lon_deg.abs() > 170.0 => Some(0.0),
        a => Some(a / 60.0),
    }
}

/// The slope of a facet in the band around latitude `band_deg`, deg.
fn slope(band_deg: f64) -> f64 {
    band_deg.abs()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A share `p` with an interval of +-0.02 within [0, 1].
fn share(p: f64) -> FacetShare {
    FacetShare {
        p,
        low: (p - 0.02).max(0.0),
        high: (p + 0.02).min(1.0),
    }
}

/// A UV sphere of `lons` x `bands` facets (poles as vertices), its facets' numbers made up
/// by `p_stable` and `slope`.
fn sphere(lons: usize, bands: usize) -> Site {
    let step = 180.0 / bands as f64;
    let dir = |lat: f64, lon: f64| {
        let (lat, lon) = (lat.to_radians(), lon.to_radians());
        [
            RADIUS_M * lat.cos() * lon.cos(),
            RADIUS_M * lat.cos() * lon.sin(),
            RADIUS_M * lat.sin(),
        ]
    };
    let mut vertices = vec![[0.0, 0.0, RADIUS_M], [0.0, 0.0, -RADIUS_M]];
    for j in 1..bands {
        for k in 0..lons {
            let lon = LON0 + k as f64 * 360.0 / lons as f64;
            vertices.push(dir(90.0 - step * j as f64, lon));
        }
    }
    // Vertex k of ring j (1 to bands - 1), the poles 0 and 1.
    let ring = |j: usize, k: usize| (2 + (j - 1) * lons + k % lons) as u32;
    let mut triangles = Vec::new();
    let mut band_of = Vec::new();
    for j in 0..bands {
        for k in 0..lons {
            // Counter-clockwise seen from outside: east is +k, north is -j.
            let quad = match j {
                0 => vec![[0, ring(1, k), ring(1, k + 1)]],
                j if j == bands - 1 => vec![[ring(j, k), 1, ring(j, k + 1)]],
                j => vec![
                    [ring(j, k), ring(j + 1, k), ring(j + 1, k + 1)],
                    [ring(j, k), ring(j + 1, k + 1), ring(j, k + 1)],
                ],
            };
            for t in quad {
                triangles.push(t);
                band_of.push(90.0 - step * (j as f64 + 0.5));
            }
        }
    }
    let facets = triangles
        .iter()
        .zip(&band_of)
        .enumerate()
        .map(|(i, (t, band))| facet(i, &vertices, *t, *band))
        .collect();
    let area_m2 = 4.0 * std::f64::consts::PI * RADIUS_M * RADIUS_M;
    Site {
        body: Body {
            name: "sphere".into(),
            vertices,
            triangles,
            density_kg_m3: 2000.0,
            spin_period_h: 12.0,
            spin_axis: [0.0, 0.0, 1.0],
            mass_kg: 2000.0 * area_m2 * RADIUS_M / 3.0,
            volume_m3: area_m2 * RADIUS_M / 3.0,
            area_m2,
        },
        facets,
    }
}

/// Facet `i`, triangle `t` of `vertices`, in the band around latitude `band`.
fn facet(i: usize, vertices: &[[f64; 3]], t: [u32; 3], band: f64) -> SiteFacet {
    let [a, b, c] = t.map(|v| vertices[v as usize]);
    let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
    let n = cross(sub(b, a), sub(c, a));
    let twice_area = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let lat = centroid[2]
        .atan2(centroid[0].hypot(centroid[1]))
        .to_degrees();
    let lon = centroid[1].atan2(centroid[0]).to_degrees();
    let g = 1e-4 * (1.0 + band.abs() / 90.0);
    let r = (centroid[0].powi(2) + centroid[1].powi(2) + centroid[2].powi(2)).sqrt();
    let shares = p_stable(band, lon).map(|p| {
        let rest = (1.0 - p) / 3.0;
        [share(p), share(rest), share(rest), share(rest)]
    });
    SiteFacet {
        facet: i as u32,
        centroid_m: centroid,
        latitude_deg: lat,
        longitude_deg: lon,
        normal: n.map(|x| x / twice_area),
        area_m2: twice_area / 2.0,
        effective_gravity_m_s2: centroid.map(|x| -g * x / r),
        gravity_m_s2: g,
        slope_deg: slope(band),
        samples: 1000 + i as u64,
        shares,
    }
}

/// Copies `file` into `TOUCHDOWN_SITE_PICTURES`, if set, to be looked at.
fn keep(file: &Path) {
    if let Ok(dir) = std::env::var("TOUCHDOWN_SITE_PICTURES") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::copy(file, Path::new(&dir).join(file.file_name().unwrap())).unwrap();
    }
}

/// A map's frame in the picture: its left, right, top and bottom pixel columns and rows
/// (the black frame's rows: the longest runs of black, 400 pixels or more, between
/// columns `from` and `to`).
fn frame(img: &image::RgbImage, from: u32, to: u32) -> (f64, f64, f64, f64) {
    let mut rows = Vec::new();
    for y in 0..img.height() {
        let (mut run, mut best) = (0, (0, 0));
        for x in from..to {
            run = if img.get_pixel(x, y).0 == [0, 0, 0] {
                run + 1
            } else {
                0
            };
            if run > best.1 - best.0 {
                best = (x + 1 - run, x);
            }
        }
        if best.1 - best.0 >= 400 {
            rows.push((y, best));
        }
    }
    assert!(rows.len() >= 2, "no frame between columns {from} and {to}");
    let (top, (left, right)) = rows[0];
    let (bottom, _) = rows[rows.len() - 1];
    (
        f64::from(left),
        f64::from(right),
        f64::from(top),
        f64::from(bottom),
    )
}

/// The pixel of the map in `frame` at longitude `lon` and latitude `lat`, deg.
fn at(img: &image::RgbImage, frame: (f64, f64, f64, f64), lon: f64, lat: f64) -> [u8; 3] {
    let (l, r, t, b) = frame;
    let x = l + (lon + 180.0) / 360.0 * (r - l);
    let y = t + (90.0 - lat) / 180.0 * (b - t);
    img.get_pixel(x.round() as u32, y.round() as u32).0
}

#[test]
fn the_map_colours_each_place_by_its_facet_s_p_stable_and_slope() {
    let dir = TempDir::new("site-map");
    let site = sphere(LONS, BANDS);
    assert_eq!(site.facets.len(), 528);
    let path = dir.join("sphere-map.png");
    site_map(&site, &path).expect("the map");
    keep(&path);
    let img = image::open(&path).expect("a PNG").to_rgb8();
    assert_eq!(img.dimensions(), (1800, 700));
    let left = frame(&img, 0, 900);
    let right = frame(&img, 900, 1800);
    // About 2 pixels a degree each way (the frames measure 700 x 540 or so): the places
    // below lie 5 deg or more (10 pixels) from any band's edge, where colours change.
    let w = left.1 - left.0;
    assert!(w > 600.0 && left.3 - left.2 > 400.0, "{left:?}");
    let expect = |lat: f64, lon: f64| p_stable_colour(p_stable(lat, lon));
    for (lon, lat, band) in [
        (40.0, 7.0, 7.5),
        (-120.0, -5.0, -7.5),
        (40.0, 22.0, 22.5),
        (-100.0, 37.0, 37.5),
        (100.0, -52.0, -52.5),
        (-100.0, 68.0, 67.5),
        (-100.0, 86.0, 82.5),
        (150.0, -86.0, -82.5),
    ] {
        assert_eq!(
            at(&img, left, lon, lat),
            expect(band, lon),
            "P(stable) at {lon}, {lat}"
        );
        let top = 90.0; // the largest slope, 82.5, rounded up to 10
        assert_eq!(
            at(&img, right, lon, lat),
            scale_colour(&SLOPE_SCALE, slope(band) / top),
            "slope at {lon}, {lat}"
        );
    }
    assert_eq!(expect(7.5, 40.0), SAFE);
    assert_eq!(expect(67.5, 40.0), NO_SHARES);
}

#[test]
fn a_facet_across_the_seam_shows_on_both_edges_and_nowhere_between() {
    let dir = TempDir::new("site-seam");
    let site = sphere(LONS, BANDS);
    let path = dir.join("sphere-map.png");
    site_map(&site, &path).expect("the map");
    let img = image::open(&path).expect("a PNG").to_rgb8();
    let left = frame(&img, 0, 900);
    // The seam's column (P(stable) 0 between 15 and 60 deg of latitude): its facets span
    // 172.5 to -172.5 deg. No pixel of their colour lies between: drawn from 172.5 across
    // the map to -172.5, they would cover the facets drawn before them at most longitudes
    // of their bands. The column ends at +-172.5 deg; 2 deg (4 pixels) more allow for the
    // outline's pixel.
    let seam = P_STABLE_SCALE[0];
    let (l, r, t, b) = left;
    let mut smeared = 0;
    for y in t as u32 + 2..b as u32 - 1 {
        for x in l as u32 + 2..r as u32 - 1 {
            let lon = -180.0 + 360.0 * (f64::from(x) - l) / (r - l);
            if lon.abs() < 170.5 && img.get_pixel(x, y).0 == seam {
                smeared += 1;
            }
        }
    }
    assert_eq!(smeared, 0, "pixels of the seam's facets inside the map");
    // ...and both edges of the map show it.
    for lat in [22.0, 37.0, -37.0, -52.0] {
        assert_eq!(at(&img, left, 177.0, lat), seam, "east edge at {lat}");
        assert_eq!(at(&img, left, -177.0, lat), seam, "west edge at {lat}");
    }
}

#[test]
fn a_map_of_nothing_or_of_bad_triangles_is_refused_and_nan_is_drawn_grey() {
    let dir = TempDir::new("site-refused");
    let mut empty = sphere(LONS, BANDS);
    empty.facets.clear();
    empty.body.triangles.clear();
    let path = dir.join("empty.png");
    let e = site_map(&empty, &path).expect_err("no facets");
    assert!(e.to_string().contains("no facets"), "{e}");
    assert!(!path.exists());
    let mut bad = sphere(LONS, BANDS);
    bad.body.triangles[5] = [0, 1, 99_999];
    let e = site_map(&bad, &path).expect_err("a missing vertex");
    assert!(e.to_string().contains("vertex 99999"), "{e}");
    let mut fewer = sphere(LONS, BANDS);
    fewer.body.triangles.pop();
    assert!(site_map(&fewer, &path).is_err());
    assert!(!path.exists());
    // Not a number anywhere: drawn, grey where a value is missing, no panic.
    let mut nan = sphere(LONS, BANDS);
    for f in &mut nan.facets {
        f.slope_deg = f64::NAN;
        f.longitude_deg = f64::NAN;
        if let Some(s) = &mut f.shares {
            s[0].p = f64::NAN;
        }
    }
    nan.body.vertices[7] = [f64::NAN; 3];
    nan.body.density_kg_m3 = f64::NAN;
    site_map(&nan, &path).expect("drawn");
    let img = image::open(&path).expect("a PNG").to_rgb8();
    let right = frame(&img, 900, 1800);
    assert_eq!(at(&img, right, 40.0, 37.0), NO_SHARES);
}
