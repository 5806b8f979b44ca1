//! `touchdown site --window-samples N` (issue 50, point 4): the sweep's samples set from
//! the body, whatever its facet count, so that the window of every facet a lander could
//! stand on expects at least N of them; `site.md` names the least-served window.

use crate::common::{TempDir, arrow_column as column, touchdown};
use crate::shape::icosphere;
use crate::site::{GENTLE, PERIOD_H, RADIUS_M, obj, samples_of};

/// The share of a sweep's samples that the window about (`slope`, `gravity`) expects, the
/// sweep drawing slopes on `[0, slope_max]` and gravities on `[g_lo, g_hi]` uniformly: the
/// window (+-`h` deg, +-`f` of the gravity) clipped to that rectangle, over its area.
fn share(
    slope: f64,
    gravity: f64,
    (slope_max, g_lo, g_hi): (f64, f64, f64),
    h: f64,
    f: f64,
) -> f64 {
    let clipped = |lo: f64, hi: f64, min: f64, max: f64| (hi.min(max) - lo.max(min)).max(0.0);
    clipped(slope - h, slope + h, 0.0, slope_max) / slope_max
        * clipped(gravity * (1.0 - f), gravity * (1.0 + f), g_lo, g_hi)
        / (g_hi - g_lo)
}

#[test]
fn window_samples_set_the_sweep_so_that_the_least_served_window_expects_them() {
    let dir = TempDir::new("site-window-samples");
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
    let run = touchdown(dir.path(), &args);
    run.assert_ok();
    let table = dir.join("map/facets.arrow");
    // The sweep's ranges, as its scenario text in the table says them (exactly).
    let file = std::fs::File::open(&table).unwrap();
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
    let meta = reader.schema().metadata().clone();
    let text: toml::Table = meta["touchdown.scenario"].parse().unwrap();
    let range = |t: &toml::Value| [t["min"].as_float().unwrap(), t["max"].as_float().unwrap()];
    let [slope_min, slope_max] = range(&text["inputs"]["slope_deg"]);
    let [g_lo, g_hi] = range(&text["gravity_m_s2"]);
    assert_eq!(slope_min, 0.0);
    // The window that expects the fewest (the defaults: +-1 deg, +-5 %), among the facets
    // flatter than 89 deg (all of this sphere's), and the samples that make it expect 40.
    let (slopes, gravities) = (
        column(&table, "slope_deg").unwrap(),
        column(&table, "gravity_m_s2").unwrap(),
    );
    let share_of = |k: usize| share(slopes[k], gravities[k], (slope_max, g_lo, g_hi), 1.0, 0.05);
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
