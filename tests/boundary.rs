//! `touchdown boundary` against `touchdown report` of a uniform sweep of the same scenario,
//! and its refusals of bad input.

use crate::common::{BadInput, TempDir, bad_args, bad_scenario, check_bad_input, touchdown};

/// The default gear with its footpads on a circle of 0.75 m, the first leg at 22.5 deg (the
/// sectors alternate between a leg and a side), friction 1.0, released from 0.5-1.0 m, a
/// hold time of 0.5 s: about 40 % stand, the allowable slope is 7-11 deg by sector, and a
/// uniform sweep of 150 000 samples takes about half a minute on 2 cores.
const SCENARIO: &str = "[lander]
footpad_radius_m = 0.75
first_leg_azimuth_deg = 22.5
[surface]
friction_coefficient = 1.0
[inputs]
release_height_m = { dist = \"uniform\", min = 0.5, max = 1.0 }
[simulation]
t_max_s = 20.0
[outcome]
hold_time_s = 0.5
";

/// A row of an allowable-slope table: samples, allowable slope, 95 % interval.
type Sector = (u64, Option<f64>, Option<(f64, f64)>);

/// The rows of an allowable-slope table: per sector, the samples, the allowable slope (if
/// any) and the 95 % interval (low, high), from the columns `samples`, `allowable` and
/// `interval` (0-based, after the sector's).
fn allowable_rows(markdown: &str, [samples, allowable, interval]: [usize; 3]) -> Vec<Sector> {
    let section = markdown
        .split("## Allowable slope")
        .nth(1)
        .unwrap_or_else(|| panic!("no allowable-slope section:\n{markdown}"));
    let deg = |cell: &str| cell.trim_end_matches(" deg").parse::<f64>().ok();
    section
        .lines()
        .filter(|l| l.starts_with("| ") && l.contains(" deg |"))
        .take(8)
        .map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).skip(2).collect();
            let range = cells[interval].trim_end_matches(" deg").split_once('–');
            (
                cells[samples].parse().expect("a sample count"),
                deg(cells[allowable]),
                range.map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap())),
            )
        })
        .collect()
}

#[test]
fn boundary_agrees_with_the_report_of_a_uniform_sweep() {
    let dir = TempDir::new("boundary");
    dir.write("s.toml", SCENARIO);
    let sweep = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--samples",
            "150000",
            "--quiet",
            "--out",
            "u.arrow",
        ],
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let report = touchdown(dir.path(), &["report", "u.arrow"]);
    report.assert_ok();
    // Another seed: the boundary's samples are not the sweep's, so the two estimates are
    // independent.
    let boundary = touchdown(
        dir.path(),
        &[
            "boundary",
            "--scenario",
            "s.toml",
            "--seed",
            "2",
            "--tolerance",
            "1.5",
            "--quiet",
        ],
    );
    boundary.assert_ok();
    let uniform = allowable_rows(&report.stdout, [0, 2, 3]);
    let found = allowable_rows(&boundary.stdout, [0, 2, 3]);
    assert_eq!((uniform.len(), found.len()), (8, 8), "{report}\n{boundary}");

    // Both are 95 % intervals of the same quantity, the report's allowable slope of the
    // scenario's distribution: where both cover it they overlap, so intervals apart would
    // mean that one of them misses it (well under 5 % per sector for two independent
    // intervals; the seeds are fixed, so the test is deterministic). Each interval must
    // also hold its own estimate.
    let mut compared = 0;
    for (k, (u, b)) in uniform.iter().zip(&found).enumerate() {
        let (Some(us), Some(bs), Some((ul, uh)), Some((bl, bh))) = (u.1, b.1, u.2, b.2) else {
            continue;
        };
        assert!(
            (ul..=uh).contains(&us) && (bl..=bh).contains(&bs),
            "sector {k}: {u:?} {b:?}"
        );
        assert!(
            ul <= bh && bl <= uh,
            "sector {k}: the report's {ul}–{uh} deg and the boundary's {bl}–{bh} deg do not \
             overlap\n{}\n{}",
            report.stdout,
            boundary.stdout
        );
        compared += 1;
    }
    assert!(compared >= 6, "{}\n{}", report.stdout, boundary.stdout);
    // And it needed fewer samples for narrower intervals. A width shrinks as n^-1/2, so a
    // uniform sweep would need (w_uniform / w_boundary)^2 times its 150 000 samples for the
    // boundary's widths (mean widths over the sectors compared): the boundary must have
    // used at most half that.
    let width = |rows: &[Sector]| {
        let w: Vec<f64> = rows
            .iter()
            .zip(&uniform)
            .zip(&found)
            .filter(|((_, u), b)| u.1.is_some() && b.1.is_some())
            .filter_map(|((r, _), _)| r.2.map(|(lo, hi)| hi - lo))
            .collect();
        w.iter().sum::<f64>() / w.len() as f64
    };
    let (wu, wb) = (width(&uniform), width(&found));
    let used: u64 = found.iter().map(|r| r.0).sum();
    let uniform_needs = 150_000.0 * (wu / wb).powi(2);
    assert!(
        wb < wu && 2.0 * used as f64 <= uniform_needs,
        "{used} samples, mean width {wb:.2} deg; the uniform sweep's {wu:.2} deg (it would \
         need {uniform_needs:.0} for the boundary's):\n{}",
        boundary.stdout
    );
    let total = format!("{used} samples simulated");
    assert!(boundary.stdout.contains(&total), "{}", boundary.stdout);
}

#[test]
fn boundary_refuses_bad_input() {
    const CASES: &[BadInput] = &[
        bad_scenario(
            "fixed slope",
            "[inputs]\nslope_deg = 10.0\n",
            &["slope_deg", "distribution"],
        ),
        bad_scenario(
            "grid slope",
            "[inputs]\nslope_deg = { dist = \"grid\", min = 0.0, max = 40.0, count = 5 }\n",
            &["slope_deg", "grid"],
        ),
        bad_scenario("not a scenario", "[lander\n", &["scenario"]),
        bad_args(
            "missing scenario file",
            &["--scenario", "nowhere.toml"],
            &["nowhere.toml"],
        ),
        bad_args("tolerance 0", &["--tolerance", "0"], &["--tolerance"]),
        bad_args(
            "tolerance as wide as the slope range",
            &["--tolerance", "1000"],
            &[
                "--tolerance 1000 deg: must be less than the width of the range of \
                 inputs.slope_deg, 45 deg (from 0 to 45 deg)",
            ],
        ),
        bad_args(
            "negative tolerance",
            &["--tolerance", "-1"],
            &["--tolerance"],
        ),
        bad_args(
            "tolerance not a number",
            &["--tolerance", "wide"],
            &["--tolerance"],
        ),
        bad_args("batch 0", &["--batch", "0"], &["--batch"]),
        bad_args("batch not a count", &["--batch", "1.5"], &["--batch"]),
        bad_args(
            "no samples per sector",
            &["--max-samples-per-sector", "0"],
            &["--max-samples-per-sector"],
        ),
        bad_args("threads 0", &["--threads", "0"], &["--threads"]),
        bad_args("unknown flag", &["--samples", "10"], &["--samples"]),
    ];
    let problems: Vec<String> = CASES
        .iter()
        .flat_map(|case| check_bad_input("boundary", case, &["touchdown boundary:"]))
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}
