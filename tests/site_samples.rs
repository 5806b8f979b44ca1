//! `touchdown site --window-samples N` (issue 50, point 4): the sweep's samples set from
//! the body, whatever its facet count, so that the window of every facet a lander could
//! stand on expects at least N of them; `site.md` names the least-served window. With
//! `--gravity-draw log-uniform` every window gets the same share in gravity.

use crate::common::{TempDir, arrow_column as column, touchdown};
use crate::shape::icosphere;
use crate::site::{GENTLE, PERIOD_H, RADIUS_M, obj, samples_of};

/// The share of a sweep's samples that the window about (`slope`, `gravity`) expects (+-`h`
/// deg, +-`f` of the gravity, clipped to the ranges), the sweep drawing slopes uniformly on
/// `[0, slope_max]` and gravities on `[g_lo, g_hi]`: uniformly, the window's area over the
/// rectangle's; uniformly in the logarithm (`log`), its share in slope times its
/// logarithmic width over the range's, `ln((1 + f)/(1 - f)) / ln(g_hi / g_lo)` unclipped.
fn share(
    slope: f64,
    gravity: f64,
    (slope_max, g_lo, g_hi): (f64, f64, f64),
    (h, f): (f64, f64),
    log: bool,
) -> f64 {
    let clipped = |lo: f64, hi: f64, min: f64, max: f64| (hi.min(max) - lo.max(min)).max(0.0);
    let (lo, hi) = (
        (gravity * (1.0 - f)).max(g_lo),
        (gravity * (1.0 + f)).min(g_hi),
    );
    let in_gravity = if log {
        (hi / lo).ln() / (g_hi / g_lo).ln()
    } else {
        clipped(lo, hi, g_lo, g_hi) / (g_hi - g_lo)
    };
    clipped(slope - h, slope + h, 0.0, slope_max) / slope_max * in_gravity
}

/// The map of the 320-facet spinning sphere made with `--window-samples 40` and `extra`, in
/// `dir`'s `map`: the facets' table's metadata and the sweep's scenario text (its ranges
/// exactly).
fn sized_map(dir: &TempDir, extra: &[&str]) -> (arrow_schema::Metadata, toml::Table) {
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 2)));
    dir.write("gentle.toml", GENTLE);
    let period = PERIOD_H.to_string();
    let args = [
        "site",
        "sphere.obj",
        "--units",
        "m",
        "--density",
        "2000",
        "--spin-period",
        &period,
        "--scenario",
        "gentle.toml",
        "--window-samples",
        "40",
        "--out-dir",
        "map",
    ];
    touchdown(dir.path(), &[&args[..], extra].concat()).assert_ok();
    let file = std::fs::File::open(dir.join("map/facets.arrow")).unwrap();
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
    let meta = reader.schema().metadata().clone();
    let text: toml::Table = meta["touchdown.scenario"].parse().unwrap();
    (meta, text)
}

/// The `min` and `max` of a distribution in a scenario's text.
fn range(t: &toml::Value) -> [f64; 2] {
    [t["min"].as_float().unwrap(), t["max"].as_float().unwrap()]
}

#[test]
fn window_samples_set_the_sweep_so_that_the_least_served_window_expects_them() {
    let dir = TempDir::new("site-window-samples");
    let (meta, text) = sized_map(&dir, &[]);
    let table = dir.join("map/facets.arrow");
    let [slope_min, slope_max] = range(&text["inputs"]["slope_deg"]);
    let [g_lo, g_hi] = range(&text["gravity_m_s2"]);
    assert_eq!(slope_min, 0.0);
    // The window that expects the fewest (the defaults: +-1 deg, +-5 %), among the facets
    // flatter than 89 deg (all of this sphere's), and the samples that make it expect 40.
    let (slopes, gravities) = (
        column(&table, "slope_deg").unwrap(),
        column(&table, "gravity_m_s2").unwrap(),
    );
    let share_of = |k: usize| {
        share(
            slopes[k],
            gravities[k],
            (slope_max, g_lo, g_hi),
            (1.0, 0.05),
            false,
        )
    };
    let least = (0..slopes.len())
        .map(share_of)
        .fold(f64::INFINITY, f64::min);
    let needed = (40.0 / least).ceil() as u64;
    assert_eq!(meta["touchdown.samples"], needed.to_string());
    // site.md names it: one of the windows of least share (on this sphere, several facets
    // at the equator tie: slope 0, the window cut in half, and the smallest gravity).
    let md = std::fs::read_to_string(dir.join("map/site.md")).unwrap();
    let line = format!(
        "The least-served window expects 40.0 samples (--window-samples 40: the sweep's \
         {needed} samples were set for it): facet "
    );
    let named: usize = md
        .lines()
        .find_map(|l| l.strip_prefix(&line))
        .and_then(|r| r.split(',').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{line:?} not in\n{md}"));
    assert!(share_of(named) <= least * (1.0 + 1e-12), "facet {named}");
    // Every window holds about what it expects: the fewest, 40 on average, is within four
    // standard deviations (sqrt 40 = 6.3) of it, 15 or more (a chance of about 1e-5 for
    // each of the 320 windows, the sweep's seed fixed).
    let counts = samples_of(&table);
    assert!(counts.iter().all(|&n| n >= 15), "{counts:?}");
}

#[test]
fn gravity_drawn_in_its_logarithm_gives_every_window_its_share_with_fewer_samples() {
    let dir = TempDir::new("site-window-samples-log");
    let (meta, text) = sized_map(&dir, &["--gravity-draw", "log-uniform"]);
    let table = dir.join("map/facets.arrow");
    let g = &text["gravity_m_s2"];
    assert_eq!(g["dist"].as_str(), Some("log-uniform"), "{text}");
    let [_, slope_max] = range(&text["inputs"]["slope_deg"]);
    let [g_lo, g_hi] = range(g);
    let ranges = (slope_max, g_lo, g_hi);
    let (slopes, gravities) = (
        column(&table, "slope_deg").unwrap(),
        column(&table, "gravity_m_s2").unwrap(),
    );
    // The samples that make the least share expect 40: fewer than the uniform draw needs
    // (its least window, at the smallest gravity, is the narrowest there).
    let least = |f: &dyn Fn(f64, f64) -> f64| {
        (0..slopes.len())
            .map(|k| f(slopes[k], gravities[k]))
            .fold(f64::INFINITY, f64::min)
    };
    let needed = (40.0 / least(&|s, g| share(s, g, ranges, (1.0, 0.05), true))).ceil() as u64;
    let uniform = (40.0 / least(&|s, g| share(s, g, ranges, (1.0, 0.05), false))).ceil() as u64;
    assert_eq!(meta["touchdown.samples"], needed.to_string());
    assert!(needed < uniform, "{needed} against {uniform}");
    // The sweep drew them so: each quarter of the range's logarithm holds a quarter of the
    // samples, within five standard deviations of the binomial count.
    let drawn = column(&dir.join("map/sweep.arrow"), "gravity_m_s2").unwrap();
    assert_eq!(drawn.len() as u64, needed);
    let n = drawn.len() as f64;
    for q in 0..4 {
        let (a, b) = (
            g_lo * (g_hi / g_lo).powf(f64::from(q) / 4.0),
            g_lo * (g_hi / g_lo).powf(f64::from(q + 1) / 4.0),
        );
        let inside = drawn.iter().filter(|&&x| a <= x && x < b).count() as f64;
        assert!(
            (inside - n / 4.0).abs() < 5.0 * (n * 0.25 * 0.75).sqrt(),
            "quarter {q}: {inside} of {n}"
        );
    }
    // site.md says how it drew; every window holds about its 40 or more (15: four standard
    // deviations below, as in the uniform test).
    let md = std::fs::read_to_string(dir.join("map/site.md")).unwrap();
    assert!(
        md.contains("m/s^2 (uniformly in the logarithm); each facet"),
        "{md}"
    );
    assert!(
        md.contains(&format!(
            "The least-served window expects 40.0 samples (--window-samples 40: the sweep's \
             {needed} samples were set for it)"
        )),
        "{md}"
    );
    let counts = samples_of(&table);
    assert!(counts.iter().all(|&n| n >= 15), "{counts:?}");
}

#[test]
fn window_samples_are_refused_with_samples_or_as_0() {
    let dir = TempDir::new("site-window-samples-refused");
    dir.write("sphere.obj", &obj(&icosphere(RADIUS_M, 1)));
    let base = [
        "site",
        "sphere.obj",
        "--units",
        "m",
        "--density",
        "2000",
        "--spin-period",
        "3.3",
    ];
    for (extra, says) in [
        (
            &["--samples", "1000", "--window-samples", "10"][..],
            "cannot be used with",
        ),
        (
            &["--window-samples", "0"][..],
            "--window-samples must be at least 1",
        ),
    ] {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        let run = touchdown(dir.path(), &args);
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(says), "{says:?}: {run}");
    }
    assert!(!dir.join("site").exists(), "nothing written");
}
