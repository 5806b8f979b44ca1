//! Outcome shares on a terrain (`report --slope-distribution`): a sweep over a broad range
//! of slopes, weighed onto a terrain's slope distribution, gives the shares of a sweep drawn
//! from that distribution directly, within their intervals; sweeps that cannot be weighed
//! are refused with the reason.

use crate::common::{TempDir, set_down_lines, touchdown};

/// Landers set down gently (drops of at most 1 cm, no attitude or rate errors) at any yaw,
/// on a gripping surface, so that the slope decides: stable below about 45 deg, tipped or
/// sliding above. The slope line is the test's.
const BASE: &str = concat!(
    "seed = 1
[surface]
friction_coefficient = 1.5
[inputs]
SLOPE
yaw_deg = { dist = \"uniform\", min = 0.0, max = 360.0 }
",
    set_down_lines!("{ dist = \"uniform\", min = 0.0, max = 0.01 }", "0.0"),
    "[initial]
attitude_reference = \"surface\"
[simulation]
t_max_s = 20.0
"
);

/// Runs a sweep of `slope` (a `slope_deg` value) with `samples` and `seed` into `out`;
/// gives its stable, tipped and sliding counts.
fn sweep(dir: &TempDir, slope: &str, samples: u64, seed: u64, out: &str) -> [u64; 3] {
    let name = format!("{out}.toml");
    dir.write(
        &name,
        &BASE.replace("SLOPE", &format!("slope_deg = {slope}")),
    );
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            &name,
            "--samples",
            &samples.to_string(),
            "--seed",
            &seed.to_string(),
            "--quiet",
            "--out",
            out,
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    ["stable", "tipped", "sliding"].map(|o| {
        run.stdout
            .lines()
            .find(|l| l.trim_start().starts_with(o))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("no {o} count in {run}"))
    })
}

/// The share and its standard error (from the 95 % interval's half width) of `outcome` in
/// the terrain section of a report.
fn weighted(report: &str, outcome: &str) -> (f64, f64) {
    let section = report
        .split("## On a terrain")
        .nth(1)
        .unwrap_or_else(|| panic!("no terrain section in\n{report}"));
    let row = section
        .lines()
        .find(|l| l.starts_with(&format!("| {outcome} |")))
        .unwrap_or_else(|| panic!("no {outcome} row in\n{section}"));
    let numbers: Vec<f64> = row
        .split(['|', '%', '–'])
        .filter_map(|c| c.trim().parse().ok())
        .collect();
    assert_eq!(numbers.len(), 3, "{row}");
    (
        numbers[0] / 100.0,
        (numbers[2] - numbers[1]) / 100.0 / (2.0 * 1.959_964),
    )
}

fn report(dir: &TempDir, sweep: &str, terrain: &str) -> String {
    let run = touchdown(
        dir.path(),
        &["report", sweep, "--slope-distribution", terrain],
    );
    assert_eq!(run.code, Some(0), "{run}");
    run.stdout
}

#[test]
fn a_broad_sweep_weighed_onto_a_terrain_gives_the_shares_drawn_from_it() {
    let dir = TempDir::new("weighting");
    // The sweep: slopes normal about 30 deg, sd 15, within 0-60 (a density far from the
    // terrains', so that weights that forgot it would show).
    let n = 40_000;
    let broad = sweep(
        &dir,
        "{ dist = \"normal\", mean = 30.0, sd = 15.0, min = 0.0, max = 60.0 }",
        n,
        1,
        "broad.arrow",
    );

    // Terrain 1: normal about 42 deg, sd 5 (0.016 % above 60 deg, left out; the direct
    // sweep is truncated there too, so both estimate the same conditional shares).
    let text = report(&dir, "broad.arrow", "normal:42:5");
    let direct = sweep(
        &dir,
        "{ dist = \"normal\", mean = 42.0, sd = 5.0, min = 0.0, max = 60.0 }",
        n,
        2,
        "direct.arrow",
    );
    // Terrain 2: bins, 30 % of the slopes uniform on 20-35 deg and 70 % on 35-50; drawn
    // directly as two sweeps mixed 0.3 / 0.7.
    dir.write(
        "bins.csv",
        "slope_min_deg,slope_max_deg,probability\n20,35,3\n35,50,7\n",
    );
    let bins_text = report(&dir, "broad.arrow", "bins.csv");
    let (na, nb) = (12_000, 28_000);
    let low = sweep(
        &dir,
        "{ dist = \"uniform\", min = 20.0, max = 35.0 }",
        na,
        3,
        "low.arrow",
    );
    let high = sweep(
        &dir,
        "{ dist = \"uniform\", min = 35.0, max = 50.0 }",
        nb,
        4,
        "high.arrow",
    );

    let mut rows = Vec::new();
    for (k, outcome) in ["stable", "tipped", "sliding"].iter().enumerate() {
        let share = |c: &[u64; 3], n: u64| c[k] as f64 / n as f64;
        let var = |p: f64, n: u64| p * (1.0 - p) / n as f64;
        // Terrain 1.
        let (pw, sw) = weighted(&text, outcome);
        let pd = share(&direct, n);
        let sd = var(pd, n).sqrt();
        // Terrain 2.
        let (qw, tw) = weighted(&bins_text, outcome);
        let (pa, pb) = (share(&low, na), share(&high, nb));
        let qd = 0.3 * pa + 0.7 * pb;
        let td = (0.09 * var(pa, na) + 0.49 * var(pb, nb)).sqrt();
        // Three standard errors of the difference: a false failure has odds of 1 in 370
        // per comparison (the seeds are fixed, so the test is deterministic).
        for (what, w, s, d, e) in [
            ("normal:42:5", pw, sw, pd, sd),
            ("bins.csv", qw, tw, qd, td),
        ] {
            let bound = 3.0 * (s * s + e * e).sqrt();
            rows.push(format!(
                "{what} {outcome}: weighted {w:.4} +- {s:.4}, direct {d:.4} +- {e:.4}, \
                 bound {bound:.4}"
            ));
            assert!(
                (w - d).abs() <= bound,
                "{what} {outcome}: weighted {w} against direct {d} (bound {bound})"
            );
        }
        // The weighting moves the shares: the sweep's own differ from the terrain's.
        let own = share(&broad, n);
        assert!(
            (own - pd).abs() > 5.0 * sd,
            "{outcome}: the sweep's own share {own} is the terrain's {pd}"
        );
    }
    eprintln!("{}", rows.join("\n"));
}

#[test]
fn sweeps_that_do_not_cover_the_terrain_or_cannot_be_weighed_are_refused() {
    let dir = TempDir::new("weighting-refused");
    sweep(
        &dir,
        "{ dist = \"uniform\", min = 0.0, max = 40.0 }",
        200,
        1,
        "u.arrow",
    );
    sweep(
        &dir,
        "{ dist = \"grid\", min = 0.0, max = 40.0, count = 5 }",
        200,
        1,
        "grid.arrow",
    );
    dir.write("t.csv", "slope_deg\n10\n20\n");
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--inputs",
            "t.csv",
            "--quiet",
            "--out",
            "table.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    for (sweep, terrain, expect) in [
        ("u.arrow", "rayleigh:20", "% of its slopes above 40 deg"),
        ("u.arrow", "uniform:10:50", "do not cover the terrain's"),
        (
            "grid.arrow",
            "uniform:10:20",
            "uniform or normal distribution",
        ),
        ("table.arrow", "uniform:10:20", "from a table of inputs"),
        (
            "u.arrow",
            "rayleigh:-1",
            "a scale (SD, SIGMA, MEAN) of at least",
        ),
        ("u.arrow", "none.csv", "nor a readable CSV file"),
    ] {
        let run = touchdown(
            dir.path(),
            &["report", sweep, "--slope-distribution", terrain],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(expect), "{expect:?}: {run}");
        assert!(run.stdout.is_empty(), "{run}");
    }
}
