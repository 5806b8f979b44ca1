//! `[limits]`: the limits each sample broke, and `report`'s "stable within limits".

use super::Columns;
use crate::common::{TempDir, touchdown};

/// `scenarios/flat.toml` (gentle touchdowns on 90 psi dampers: 42 % stable) with the
/// limits `limits`.
fn with_limits(limits: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/flat.toml");
    let flat = std::fs::read_to_string(path).unwrap();
    format!("{flat}\n[limits]\n{limits}")
}

/// The row of `report` naming `name`: its count.
fn report_count(report: &str, name: &str) -> u64 {
    let line = report
        .lines()
        .find(|l| l.starts_with(&format!("| {name} |")))
        .unwrap_or_else(|| panic!("no row {name} in\n{report}"));
    line.split('|').nth(2).unwrap().trim().parse().unwrap()
}

#[test]
fn broken_limits_are_listed_and_the_report_counts_stable_within_limits() {
    // An axial limit of 150 N and an acceleration limit of 2 m/s^2, which some of 400
    // samples exceed and others do not (their medians: 128 N, 1.6 m/s^2): a sample lists
    // `axial_force` exactly when a leg's peak axial load is above 150 N, `acceleration`
    // exactly when its peak CG acceleration is above 2 m/s^2, in that order; `report` counts the stable samples that list none,
    // and the samples that broke each limit, as the file's own columns give them.
    let dir = TempDir::new("struts-limits");
    dir.write(
        "limits.toml",
        &with_limits("axial_force_n = 150.0\nacceleration_m_s2 = 2.0\n"),
    );
    super::sweep(
        &dir,
        &[
            "--scenario",
            "limits.toml",
            "--samples",
            "400",
            "--out",
            "l.arrow",
            "--quiet",
        ],
    );
    let file = Columns::in_dir(&dir, "l.arrow");
    let broken = file.strings("limits_broken");
    let outcomes = file.strings("outcome");
    let accelerations = file.f64s("peak_acceleration_m_s2");
    let axial: Vec<Vec<f64>> = (0..4)
        .map(|k| file.f64s(&format!("leg{k}_peak_axial_force_n")))
        .collect();
    let (mut within, mut over_axial, mut over_acceleration) = (0, 0, 0);
    for i in 0..broken.len() {
        let axial_over = axial.iter().any(|a| a[i] > 150.0);
        let acceleration_over = accelerations[i] > 2.0;
        let expected: Vec<&str> = [
            (axial_over, "axial_force"),
            (acceleration_over, "acceleration"),
        ]
        .iter()
        .filter(|x| x.0)
        .map(|x| x.1)
        .collect();
        assert_eq!(broken[i], expected.join(","), "sample {i}");
        within += u64::from(outcomes[i] == "stable" && broken[i].is_empty());
        over_axial += u64::from(axial_over);
        over_acceleration += u64::from(acceleration_over);
    }
    println!(
        "400 samples: {within} stable within limits, {over_axial} over the axial limit, {over_acceleration} over the acceleration limit"
    );
    let some = |n: u64| n > 0 && n < 400;
    assert!(
        some(within) && some(over_axial) && some(over_acceleration),
        "the limits split the samples"
    );
    let report = touchdown(dir.path(), &["report", "l.arrow"]);
    report.assert_ok();
    let r = &report.stdout;
    assert_eq!(report_count(r, "stable within limits"), within, "{r}");
    assert_eq!(
        report_count(r, "broke `axial_force`: peak axial strut load above 150 N"),
        over_axial
    );
    assert_eq!(
        report_count(
            r,
            "broke `acceleration`: peak CG acceleration above 2 m/s^2"
        ),
        over_acceleration
    );
}

#[test]
fn bad_limits_are_refused_naming_the_key() {
    // Exit 2 and the key named, before any work: a negative or zero load, a key that is no
    // limit, a minimum stroke margin without dampers.
    let dir = TempDir::new("struts-bad-limits");
    for (text, key) in [
        (
            with_limits("axial_force_n = -5.0\n"),
            "limits.axial_force_n",
        ),
        (with_limits("side_force_n = 0.0\n"), "limits.side_force_n"),
        (
            with_limits("acceleration_m_s2 = \"high\"\n"),
            "limits.acceleration_m_s2",
        ),
        (
            with_limits("stroke_margin_m = -0.001\n"),
            "limits.stroke_margin_m",
        ),
        (with_limits("axial_force = 100.0\n"), "limits.axial_force"),
        (
            "[damper]\nenabled = false\n\n[limits]\nstroke_margin_m = 0.01\n".to_string(),
            "limits.stroke_margin_m",
        ),
    ] {
        dir.write("bad.toml", &text);
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                "bad.toml",
                "--samples",
                "8",
                "--out",
                "b.arrow",
            ],
        );
        assert_eq!(run.code, Some(2), "{text}\n{run}");
        assert!(run.stderr.contains(key), "{text}: {key} not named\n{run}");
        assert!(!dir.join("b.arrow").exists());
    }
}
