//! The pictures of a landing-site map (issues 34 and 45): the map picture draws each facet
//! at its longitude and latitude, in Mollweide's equal-area projection, as its true outline
//! (a facet takes the share of the map that it takes of the sphere of directions), in the
//! colour of its P(stable) and of its slope, crossing the seam without smearing. The 3D
//! page's tests are in `site_page`.
//!
//! The site is made up here: a UV sphere whose facets' numbers are functions of their
//! latitude band (and, in the seam's column, of their longitude), so the colour of every
//! place of the map is known. `TOUCHDOWN_SITE_PICTURES=DIR` copies the pictures into DIR.

use crate::common::TempDir;
use std::path::Path;
use touchdown::plot::site::{
    NO_SAMPLES, NO_SHARES, P_STABLE_SCALE, SAFE, SLOPE_SCALE, mollweide, p_stable_colour,
    scale_colour, site_map,
};
use touchdown::site::{Body, FacetShare, Site, SiteFacet};
use touchdown::view::site::site_page;

/// Longitudes and latitude bands of the test sphere: 24 x 12, 15 deg each, 528 facets.
pub(crate) const LONS: usize = 24;
pub(crate) const BANDS: usize = 12;
/// The sphere's vertices sit at longitudes 7.5 + 15 k, so that a column of facets
/// straddles the +-180 deg seam (vertices at 172.5 and -172.5 deg).
const LON0: f64 = 7.5;
pub(crate) const RADIUS_M: f64 = 200.0;

/// P(stable) of a facet in the band around latitude `band_deg` (its middle) with its
/// centroid at longitude `lon_deg`: no samples above 60 deg of latitude, a landing site
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

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [(1, 2), (2, 0), (0, 1)].map(|(i, j)| a[i] * b[j] - a[j] * b[i])
}

/// A share `p` with an interval of +-0.004 within [0, 1]: a landing site at 0.995.
fn share(p: f64) -> FacetShare {
    FacetShare {
        p,
        low: (p - 0.004).max(0.0),
        high: (p + 0.004).min(1.0),
    }
}

/// The colour of a facet of P(stable) `p` on the map: a landing site from 0.994 (its
/// interval's low end 0.99), no samples without shares (every facet here could be stood
/// on).
fn colour_of(p: Option<f64>) -> [u8; 3] {
    match p {
        Some(p) if p >= 0.994 => SAFE,
        Some(p) => p_stable_colour(Some(p)),
        None => NO_SAMPLES,
    }
}

/// A UV sphere of `lons` x `bands` facets (poles as vertices), its facets' numbers made up
/// by `p_stable` and `slope`.
pub(crate) fn sphere(lons: usize, bands: usize) -> Site {
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
    let (mut triangles, mut facets) = (Vec::new(), Vec::new());
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
                facets.push(facet(
                    triangles.len(),
                    &vertices,
                    t,
                    90.0 - step * (j as f64 + 0.5),
                ));
                triangles.push(t);
            }
        }
    }
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
            centre_of_mass_m: [0.0; 3],
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
    let r = (centroid[0].powi(2) + centroid[1].powi(2) + centroid[2].powi(2)).sqrt();
    let lat = (centroid[2] / r).asin().to_degrees();
    let lon = centroid[1].atan2(centroid[0]).to_degrees();
    let g = 1e-4 * (1.0 + band.abs() / 90.0);
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
        // Any number that differs from facet to facet: the page shows it as it is given.
        roughness_deg: 0.1 + 0.0123 * i as f64,
        samples: 1000 + i as u64,
        shares,
    }
}

/// Copies `file` into `TOUCHDOWN_SITE_PICTURES`, if set, to be looked at.
pub(crate) fn keep(file: &Path) {
    if let Ok(dir) = std::env::var("TOUCHDOWN_SITE_PICTURES") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::copy(file, Path::new(&dir).join(file.file_name().unwrap())).unwrap();
    }
}

/// Half the width and half the height of Mollweide's map, in its own units.
const HALF_WIDTH: f64 = 2.0 * std::f64::consts::SQRT_2;
const HALF_HEIGHT: f64 = std::f64::consts::SQRT_2;

/// The frame of the map from column `from` (the map's 750 columns, left of its colour
/// bar): the box round its edge, the only pure black drawn there (below the title).
fn frame(img: &image::RgbImage, from: u32) -> Frame {
    let (mut l, mut r, mut t, mut b) = (u32::MAX, 0, u32::MAX, 0);
    for y in 50..img.height() {
        for x in from..from + 750 {
            if img.get_pixel(x, y).0 == [0, 0, 0] {
                (l, r, t, b) = (l.min(x), r.max(x), t.min(y), b.max(y));
            }
        }
    }
    assert!(r > l + 400 && b > t + 200, "no map from column {from}");
    let px = f64::from;
    (px(l), px(r), px(t), px(b))
}

/// The map of `site` written as `name` into `dir` and read back, with its two frames
/// (P(stable)'s and the slope's).
fn drawn(site: &Site, dir: &TempDir, name: &str) -> (image::RgbImage, Frame, Frame) {
    let path = dir.join(name);
    site_map(site, &path).expect("the map");
    keep(&path);
    let img = image::open(&path).expect("a PNG").to_rgb8();
    let (left, right) = (frame(&img, 0), frame(&img, 900));
    (img, left, right)
}

/// A map's frame in the picture: its left, right, top and bottom pixel columns and rows.
type Frame = (f64, f64, f64, f64);

/// The pixel of the map in `frame` at longitude `lon` and latitude `lat`, deg.
fn at(img: &image::RgbImage, frame: Frame, lon: f64, lat: f64) -> [u8; 3] {
    let (l, r, t, b) = frame;
    let (x, y) = mollweide(lon, lat);
    let x = l + (x + HALF_WIDTH) / (2.0 * HALF_WIDTH) * (r - l);
    let y = t + (HALF_HEIGHT - y) / (2.0 * HALF_HEIGHT) * (b - t);
    img.get_pixel(x.round() as u32, y.round() as u32).0
}

/// The longitude of pixel (`x`, `y`) of the map in `frame`, deg, by Mollweide's inverse
/// (`lon = pi x / (2 sqrt 2 cos t)`, `sin t = y / sqrt 2`): beyond +-180 outside the map.
fn lon_at(frame: Frame, x: u32, y: u32) -> f64 {
    let (l, r, t, b) = frame;
    let mx = -HALF_WIDTH + (f64::from(x) - l) / (r - l) * 2.0 * HALF_WIDTH;
    let my = HALF_HEIGHT - (f64::from(y) - t) / (b - t) * 2.0 * HALF_HEIGHT;
    let theta = (my / HALF_HEIGHT).clamp(-1.0, 1.0).asin();
    (std::f64::consts::PI * mx / (HALF_WIDTH * theta.cos())).to_degrees()
}

#[test]
fn the_map_colours_each_place_by_its_facet_s_p_stable_and_slope() {
    let dir = TempDir::new("site-map");
    let (img, left, right) = drawn(&sphere(LONS, BANDS), &dir, "sphere-map.png");
    assert_eq!(img.dimensions(), (1800, 560));
    // About 1.9 pixels a degree at the equator (the map's ellipse is some 680 x 340): the
    // places below lie 5 deg or more from any band's edge, where colours change.
    assert!(
        left.1 - left.0 > 600.0 && left.3 - left.2 > 300.0,
        "{left:?}"
    );
    let expect = |lat: f64, lon: f64| colour_of(p_stable(lat, lon));
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
        // The slope's scale: 0 to 90 deg, for every body.
        let slope_colour = scale_colour(&SLOPE_SCALE, slope(band) / 90.0);
        let got = (at(&img, left, lon, lat), at(&img, right, lon, lat));
        assert!(
            of_colour(got.0, expect(band, lon)) && of_colour(got.1, slope_colour),
            "{lon}, {lat}: {got:?}"
        );
    }
    assert_eq!((expect(7.5, 40.0), expect(67.5, 40.0)), (SAFE, NO_SAMPLES));
}

#[test]
fn a_facet_around_a_pole_covers_the_map_above_it() {
    // A tetrahedron on one vertex, at the south pole: its top face rings the north pole
    // (vertices at latitude 19.5 deg, longitudes 0, 120 and 240), its sides meet below.
    let (h, s) = (RADIUS_M / 3.0, RADIUS_M * 8f64.sqrt() / 3.0);
    let corner = |l: f64| [s * l.to_radians().cos(), s * l.to_radians().sin(), h];
    let vertices = vec![
        corner(0.0),
        corner(120.0),
        corner(240.0),
        [0.0, 0.0, -RADIUS_M],
    ];
    let triangles = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]];
    // The top a landing site, the sides without shares.
    let bands = [0.0, -75.0, -75.0, -75.0];
    let mut site = sphere(4, 2);
    site.facets = (0..4)
        .map(|i| facet(i, &vertices, triangles[i], bands[i]))
        .collect();
    (site.body.vertices, site.body.triangles) = (vertices, triangles.to_vec());
    let (img, left, _) = drawn(&site, &TempDir::new("site-pole"), "tetrahedron.png");
    // Its edges run 35 deg above the equator or lower: above them, the top all round.
    for (lon, lat, colour) in [
        (-150.0, 60.0, SAFE),
        (10.0, 86.0, SAFE),
        (170.0, 50.0, SAFE),
        (50.0, -50.0, NO_SAMPLES),
    ] {
        let got = at(&img, left, lon, lat);
        assert!(of_colour(got, colour), "{lon}, {lat}: {got:?}");
    }
}

#[test]
fn a_facet_across_the_seam_shows_on_both_edges_and_nowhere_between() {
    let (img, left, _) = drawn(&sphere(LONS, BANDS), &TempDir::new("site-seam"), "seam.png");
    // The seam's column (P(stable) 0 between 15 and 60 deg of latitude): its facets span
    // 172.5 to -172.5 deg. No pixel of their colour lies between: drawn from 172.5 across
    // the map to -172.5, they would cover the facets drawn before them at most longitudes
    // of their bands. The column ends at +-172.5 deg; 4 pixels more allow for the outline's
    // pixel and the corners' rounding (a pixel spans 360 deg over the map's width at its
    // row, which narrows towards the poles: 0.53 deg at the equator, 0.8 at 60 deg).
    let seam = P_STABLE_SCALE[0];
    let (l, r, t, b) = left;
    let mut smeared = Vec::new();
    for y in t as u32 + 2..b as u32 - 1 {
        let row = 1.0 - 2.0 * (f64::from(y) - t) / (b - t);
        let per_pixel = 360.0 / ((r - l) * (1.0 - row * row).sqrt());
        for x in l as u32 + 2..r as u32 - 1 {
            let lon = lon_at(left, x, y);
            if lon.abs() < 172.5 - 4.0 * per_pixel && img.get_pixel(x, y).0 == seam {
                smeared.push((x, y, lon));
            }
        }
    }
    assert!(
        smeared.is_empty(),
        "pixels of the seam's facets inside the map: {smeared:?}"
    );
    // ...and both edges of the map show it.
    for lat in [22.0, 37.0, -37.0, -52.0] {
        assert!(
            of_colour(at(&img, left, 177.0, lat), seam),
            "east edge at {lat}"
        );
        assert!(
            of_colour(at(&img, left, -177.0, lat), seam),
            "west edge at {lat}"
        );
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
        (f.slope_deg, f.longitude_deg) = (f64::NAN, f64::NAN);
        if let Some(s) = &mut f.shares {
            s[0].p = f64::NAN;
        }
    }
    nan.body.vertices[7] = [f64::NAN; 3];
    nan.body.density_kg_m3 = f64::NAN;
    let (img, _, right) = drawn(&nan, &dir, "nan.png");
    assert_eq!(at(&img, right, 40.0, 37.0), NO_SHARES);
}

/// Issue 45: the slope's scale runs from 0 to 90 deg on every map, whatever the steepest
/// facet (before: to the steepest rounded up, 0-150 deg here), so that maps compare; a
/// steeper facet takes the scale's top colour.
#[test]
fn the_slope_scale_is_0_to_90_deg_for_every_body() {
    let mut site = sphere(LONS, BANDS);
    for f in &mut site.facets {
        if f.latitude_deg > 75.0 {
            // The effective gravity off the ground, as on a fast spinner.
            f.slope_deg = 150.0;
        }
    }
    let (img, _, right) = drawn(&site, &TempDir::new("site-slope-scale"), "slopes.png");
    for (lon, lat, slope) in [
        (40.0, 37.0, 37.5),
        (-100.0, -52.0, 52.5),
        (-100.0, 86.0, 90.0),
    ] {
        let got = at(&img, right, lon, lat);
        let expect = scale_colour(&SLOPE_SCALE, slope / 90.0);
        assert!(
            of_colour(got, expect),
            "{lon}, {lat}: {got:?} against {expect:?}"
        );
    }
}

/// The solid angle of the triangle `t` seen from the origin, sr (van Oosterom and
/// Strackee 1983).
fn solid_angle(t: [[f64; 3]; 3]) -> f64 {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let [a, b, c] = t;
    let n = |v: [f64; 3]| dot(v, v).sqrt();
    let triple = dot(a, cross(b, c));
    let below = n(a) * n(b) * n(c) + dot(a, b) * n(c) + dot(a, c) * n(b) + dot(b, c) * n(a);
    2.0 * triple.abs().atan2(below)
}

/// Whether `pixel` is `colour`, or `colour` under the map's faint graticule (darkened).
fn of_colour(pixel: [u8; 3], colour: [u8; 3]) -> bool {
    let (p, c) = (pixel.map(f64::from), colour.map(f64::from));
    let k = (p[0] * c[0] + p[1] * c[1] + p[2] * c[2]) / (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    (0.7..=1.0 + 1e-9).contains(&k) && (0..3).all(|i| (p[i] - k * c[i]).abs() <= 3.0)
}

/// Issue 45: a facet takes the share of the map that it takes of the directions from the
/// body's centre (Mollweide's projection is equal-area, and the facet is drawn as its true
/// outline, its straight edges curved on the map): a polar facet (pole to 60 deg, 60 deg
/// wide) and one at the equator, each within the pixels along its border of its solid
/// angle's share. The equirectangular map before drew the polar one at 2.9 times that.
#[test]
fn each_facet_takes_its_share_of_the_map_near_the_poles_too() {
    let mut site = sphere(6, 6);
    // Facet 0 is the fan's first at the north pole; the first facet of the third band
    // (30 deg to the equator) follows the fan's 6 and the second band's 12: 18.
    let (polar, equatorial) = (0, 18);
    for (i, f) in site.facets.iter_mut().enumerate() {
        f.shares = match i {
            0 => Some([share(0.995), share(0.0), share(0.0), share(0.005)]),
            18 => Some([share(0.5), share(0.5), share(0.0), share(0.0)]),
            _ => None,
        };
    }
    let (img, left, _) = drawn(&site, &TempDir::new("site-area"), "areas.png");
    let (l, r, t, b) = left;
    let mut inside = 0u64;
    let mut counts = [0u64; 2];
    let mut border = [0u64; 2];
    let colours = [SAFE, p_stable_colour(Some(0.5))];
    for y in t as u32 + 1..b as u32 {
        for x in l as u32 + 1..r as u32 {
            if lon_at(left, x, y).abs() >= 180.0 {
                continue;
            }
            inside += 1;
            for k in 0..2 {
                if of_colour(img.get_pixel(x, y).0, colours[k]) {
                    counts[k] += 1;
                    let near = [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|(dx, dy)| {
                        let p = img.get_pixel((x as i32 + dx) as u32, (y as i32 + dy) as u32);
                        !of_colour(p.0, colours[k])
                    });
                    border[k] += u64::from(near);
                }
            }
        }
    }
    for (k, facet) in [polar, equatorial].into_iter().enumerate() {
        let tri = site.body.triangles[facet].map(|v| site.body.vertices[v as usize]);
        let expected = solid_angle(tri) / (4.0 * std::f64::consts::PI) * inside as f64;
        assert!(
            (counts[k] as f64 - expected).abs() <= border[k] as f64,
            "facet {facet}: {} pixels against {expected:.0} (border {})",
            counts[k],
            border[k]
        );
    }
}

/// A body of 12,192 facets (as many as the Itokawa model): its map drawn, its page small.
/// (Their speed is not a test's business: the site command's summary shows it.)
#[test]
fn the_pictures_of_twelve_thousand_facets_are_drawn_and_the_page_is_small() {
    let (dir, site) = (TempDir::new("site-12k"), sphere(48, 128));
    assert_eq!(site.facets.len(), 12_192);
    let (map, page) = (dir.join("map.png"), dir.join("page.html"));
    site_map(&site, &map).expect("the map");
    site_page(&site, &page).expect("the page");
    assert!(map.is_file());
    let bytes = std::fs::metadata(&page).unwrap().len();
    // 45 kB packed (`touchdown::view::packed`); 1.28 MB as rounded JSON before.
    assert!(bytes < 100_000, "{bytes} bytes");
}
