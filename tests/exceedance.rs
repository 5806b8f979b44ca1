//! Load exceedance (issue 30 point 5): the design values `report` gives are the order
//! statistics of the sweep's own columns that their definition names, their intervals are
//! the binomial ranks around them, the stroke is there with dampers, and `plot` draws the
//! curves.

use crate::common::{TempDir, touchdown};
use std::path::Path;
use touchdown::output::columns::Table;

/// The default scenario with dampers (so that every quantity is there), cut at 20 s.
const DAMPERS: &str = "[damper]\nenabled = true\n[simulation]\nt_max_s = 20.0\n";

/// The cells of the report's exceedance row of `quantity` and `leg`: the 99 % value, its
/// interval, the 99.9 % value, its interval (the interval's ends as text), the largest.
fn row(report: &str, quantity: &str, leg: &str) -> Vec<String> {
    let section = report
        .split("## Load exceedance")
        .nth(1)
        .expect("the report has a load exceedance section");
    let line = section
        .lines()
        .find(|l| l.starts_with(&format!("| {quantity} ")) && l.contains(&format!("| {leg} |")))
        .unwrap_or_else(|| panic!("no row of {quantity}, leg {leg} in\n{section}"));
    let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
    let mut out = Vec::new();
    for c in &cells[2..4] {
        // "value (low – high)"
        let (value, rest) = c.split_once(" (").expect("a value and its interval");
        let (low, high) = rest
            .trim_end_matches(')')
            .split_once(" – ")
            .expect("two ends");
        out.extend([value.to_string(), low.to_string(), high.to_string()]);
    }
    out.push(cells[4].to_string());
    out
}

/// The sorted values of `column` (per leg: the largest leg of each sample, when `legs`),
/// scaled by `factor`.
fn sorted(path: &Path, column: &str, legs: bool, factor: f64) -> Vec<f64> {
    let t = Table::read(path, |_| true).unwrap();
    let mut v: Vec<f64> = if legs {
        let n = t.legs(column);
        assert!(n == 4, "four legs of {column}");
        (0..t.rows)
            .map(|i| {
                (0..n)
                    .map(|k| t.column(&format!("leg{k}_{column}"), path).unwrap()[i])
                    .fold(0.0, f64::max)
            })
            .collect()
    } else {
        t.column(column, path).unwrap().to_vec()
    };
    v.iter_mut().for_each(|x| *x *= factor);
    v.sort_by(f64::total_cmp);
    v
}

#[test]
fn design_values_are_the_order_statistics_of_the_sweep() {
    let dir = TempDir::new("exceedance");
    dir.write("d.toml", DAMPERS);
    let samples = 4000;
    let sweep = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "d.toml",
            "--samples",
            "4000",
            "--out",
            "d.arrow",
            "--quiet",
        ],
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let report = touchdown(dir.path(), &["report", "d.arrow"]);
    report.assert_ok();
    let path = dir.join("d.arrow");
    for (quantity, column, legs, factor) in [
        (
            "peak CG acceleration (m/s^2)",
            "peak_acceleration_m_s2",
            false,
            1.0,
        ),
        (
            "peak leg normal force (N)",
            "peak_normal_force_n",
            true,
            1.0,
        ),
        ("damper stroke (mm)", "stroke_m", true, 1e3),
    ] {
        let v = sorted(&path, column, legs, factor);
        let cells = row(
            &report.stdout,
            quantity,
            if legs { "all legs" } else { "–" },
        );
        let at = |rank: usize| format!("{:.4}", v[rank - 1]);
        // 99 %: nearest rank ceil(0.99 n) = 3960. Its interval: B ~ Bin(4000, 0.99), mean
        // 3960, sd 6.29; the ranks are where the binomial's 2.5 % tails end, within a rank
        // of the normal approximation 3960 -+ 1.96 sd = 3947.7 and 3972.3 (the unit test
        // checks the exact ranks at n = 1000 against the summed pmf).
        assert_eq!(cells[0], at(3960), "{quantity}: {cells:?}");
        let near = |cell: &str, ranks: std::ops::RangeInclusive<usize>| {
            ranks.clone().any(|r| at(r) == cell)
        };
        assert!(near(&cells[1], 3946..=3949), "{quantity}: {cells:?}");
        assert!(near(&cells[2], 3972..=3975), "{quantity}: {cells:?}");
        // 99.9 %: rank 3996; 4 samples expected above it, too few for an upper end: P(B >=
        // 4000) = 0.999^4000 = 1.8 %, so the upper end would be rank 4000 if 1.8 % <= 2.5 %:
        // it is, so the end is the largest sample.
        assert_eq!(cells[3], at(3996), "{quantity}: {cells:?}");
        assert_eq!(cells[5], at(samples), "{quantity}: {cells:?}");
        assert_eq!(cells[6], at(samples), "{quantity}: {cells:?}");
    }
    // The picture.
    touchdown(dir.path(), &["plot", "d.arrow", "--out-dir", "p"]).assert_ok();
    assert!(dir.join("p/d-exceedance.png").metadata().unwrap().len() > 10_000);
}
