//! What flew is shown (issue 29, points 6 and 8): a trace prints and stores a sample's law
//! parameters, propellant and release state as its sweep row has them; `report`
//! summarises a descent's release state; `view` shows every thruster in a legend; no step
//! is time dust.

use crate::common::{Run, TempDir, touchdown};
use std::path::{Path, PathBuf};
use touchdown::output::columns::Table;

fn scenario(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name)
}

/// `touchdown ARGS` in `dir`, which must succeed (notes on stderr allowed: a sweep's
/// landers that never touched, a trace of every N steps).
fn run_ok(dir: &TempDir, args: &[&str]) -> Run {
    let run = touchdown(dir.path(), args);
    assert_eq!(run.code, Some(0), "{run}");
    run
}

/// Law parameters are drawn from the sample's seed: a trace's are its sweep row's, bit for
/// bit. What the loop did (propellant, release state) comes from the reference there and
/// from the kernels here, which round otherwise in the last bits: 1e-6 plus 1 %, the
/// tolerance of the user's law's propellant in tests/user_law.rs (a quantised on-time may
/// flip by a rounding).
#[test]
fn a_trace_stores_and_prints_what_flew_as_its_sweep_row() {
    let dir = TempDir::new("flown_trace");
    for (file, drawn, done) in [
        (
            "hold-down.toml",
            &["hold_down_thrust_n", "hold_down_duration_s"][..],
            &["propellant_kg", "hold_down_impulse_n_s"][..],
        ),
        (
            "descent.toml",
            &[
                "attitude_kp_n_m_per_rad",
                "descent_start_altitude_m",
                "descent_release_speed_m_s",
            ][..],
            &[
                "propellant_kg",
                "release_time_s",
                "release_altitude_m",
                "release_vz_m_s",
            ][..],
        ),
    ] {
        let sweep = dir.join(&format!("{file}.arrow"));
        let s = scenario(file);
        run_ok(
            &dir,
            &[
                "sweep",
                "--scenario",
                s.to_str().unwrap(),
                "--samples",
                "3",
                "--quiet",
                "--out",
                sweep.to_str().unwrap(),
            ],
        );
        let rows = Table::read(&sweep, |_| true).unwrap();
        let trace = dir.join(&format!("{file}.trace.arrow"));
        let run = run_ok(
            &dir,
            &[
                "trace",
                "--sweep",
                sweep.to_str().unwrap(),
                "--sample",
                "2",
                "--out",
                trace.to_str().unwrap(),
            ],
        );
        let t = Table::read(&trace, |_| true).unwrap();
        for name in drawn.iter().chain(done) {
            let stored: f64 = t
                .meta
                .get(&format!("touchdown.control.{name}"))
                .unwrap_or_else(|| panic!("{file}: no touchdown.control.{name}"))
                .parse()
                .unwrap();
            let row = rows.columns[*name][2];
            if drawn.contains(name) {
                assert_eq!(stored.to_bits(), row.to_bits(), "{file}: {name}");
            } else {
                assert!(
                    (stored - row).abs() <= 1e-6 + 0.01 * row.abs(),
                    "{file}: {name} {stored} in the trace, {row} in the sweep"
                );
            }
            assert!(
                run.stdout.lines().any(|l| l.trim_start().starts_with(name)),
                "{file}: {name} not printed\n{run}"
            );
        }
    }
    // A passive trace has nothing of the kind.
    let trace = dir.join("passive.arrow");
    let run = run_ok(&dir, &["trace", "--out", trace.to_str().unwrap()]);
    let t = Table::read(&trace, |_| true).unwrap();
    assert!(!t.meta.keys().any(|k| k.starts_with("touchdown.control.")));
    assert!(!run.stdout.contains("control loop"), "{run}");
}

/// The report of a descent sweep: how many landers the descent released, and the
/// distribution of their release time, footpad height and velocity, as the columns give
/// them (the mean checked against the columns, to the 4 decimals the table prints).
#[test]
fn the_report_of_a_descent_sweep_summarises_the_release() {
    let dir = TempDir::new("flown_report");
    let sweep = dir.join("descent.arrow");
    let s = scenario("descent.toml");
    run_ok(
        &dir,
        &[
            "sweep",
            "--scenario",
            s.to_str().unwrap(),
            "--samples",
            "40",
            "--quiet",
            "--out",
            sweep.to_str().unwrap(),
        ],
    );
    let rows = Table::read(&sweep, |_| true).unwrap();
    let times: Vec<f64> = rows.columns["release_time_s"]
        .iter()
        .copied()
        .filter(|t| !t.is_nan())
        .collect();
    let report = run_ok(&dir, &["report", sweep.to_str().unwrap()]);
    let text = &report.stdout;
    assert!(text.contains("## Release of the descent"), "{text}");
    assert!(
        text.contains(&format!(
            "{} of 40 samples released by the descent law",
            times.len()
        )),
        "{text}"
    );
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let row = text
        .lines()
        .find(|l| l.starts_with("| release time (s)"))
        .expect("a release time row");
    let printed: f64 = row.split('|').nth(2).unwrap().trim().parse().unwrap();
    assert!((printed - mean).abs() <= 5e-5, "{row}: mean {mean}");
    for quantity in [
        "footpad height at release",
        "vertical velocity at release",
        "horizontal speed at release",
    ] {
        assert!(text.contains(quantity), "{quantity}\n{text}");
    }
    // A sweep without a descent has no such section.
    let passive = dir.join("hold-down.arrow");
    let s = scenario("hold-down.toml");
    run_ok(
        &dir,
        &[
            "sweep",
            "--scenario",
            s.to_str().unwrap(),
            "--samples",
            "8",
            "--quiet",
            "--out",
            passive.to_str().unwrap(),
        ],
    );
    let report = run_ok(&dir, &["report", passive.to_str().unwrap()]);
    assert!(
        !report.stdout.contains("Release of the descent"),
        "{report}"
    );
}

/// Every step of a trace of hold-down.toml ends on the control events as before, but none
/// is left as time dust: the remainder of a period after steps of 0.05 s was 7e-18 s,
/// a step of its own. (1e-12 s: `EVENT_DUST_S`; the shortest real step is a thruster's
/// on-time cut by a period's start, at least microseconds.)
#[test]
fn no_step_of_a_control_loop_is_time_dust() {
    let dir = TempDir::new("flown_dust");
    let s = scenario("hold-down.toml");
    for sample in ["0", "1", "2", "3", "4"] {
        let trace = dir.join("trace.arrow");
        run_ok(
            &dir,
            &[
                "trace",
                "--scenario",
                s.to_str().unwrap(),
                "--sample",
                sample,
                "--out",
                trace.to_str().unwrap(),
            ],
        );
        let t = Table::read(&trace, |_| true).unwrap();
        let dt = &t.columns["dt_s"];
        // The last row is the state at the decision, of length 0.
        let shortest = dt[..dt.len() - 1]
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        assert!(
            shortest >= 1e-12,
            "sample {sample}: a step of {shortest:e} s"
        );
    }
}

/// `view` of a trace of twelve thrusters: each in a chart of at most four (a legend row
/// shows four entries across the narrowest chart, as for the legs), all twelve there.
#[test]
fn view_shows_every_thruster_in_a_legend() {
    let dir = TempDir::new("flown_view");
    let s = scenario("hold-down.toml");
    let trace = dir.join("trace.arrow");
    run_ok(
        &dir,
        &[
            "trace",
            "--scenario",
            s.to_str().unwrap(),
            "--every",
            "50",
            "--out",
            trace.to_str().unwrap(),
        ],
    );
    let page = dir.join("page.html");
    run_ok(
        &dir,
        &[
            "view",
            trace.to_str().unwrap(),
            "--out",
            page.to_str().unwrap(),
        ],
    );
    let html = std::fs::read_to_string(&page).unwrap();
    let mut shown = Vec::new();
    for chart in html.split("{\"title\":").skip(1) {
        let thrusters: Vec<usize> = chart
            .split("\"series\":\"thruster")
            .skip(1)
            .map(|s| s[..s.find('_').unwrap()].parse().unwrap())
            .collect();
        assert!(
            thrusters.len() <= 4,
            "a chart of {} thrusters",
            thrusters.len()
        );
        shown.extend(thrusters);
    }
    assert_eq!(shown, (0..12).collect::<Vec<_>>());
}
