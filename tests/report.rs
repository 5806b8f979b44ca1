//! `touchdown report` on real sweeps: its outcome counts are the sweep's, and the allowable
//! slope it finds for landers set down gently is the one the static tipping limit of
//! MODEL.md section 8 gives for the same samples.

use crate::common::{Run, TempDir, set_down_lines, touchdown};

/// The default gear set down on the surface (attitude against the surface normal, no
/// errors, released from rest 1 micrometre above it), friction high enough that nothing slides: whether it
/// stands is decided by the static limit alone.
pub(crate) const GENTLE: &str = concat!(
    r#"
[surface]
friction_coefficient = 1.5
[inputs]
slope_deg = { dist = "uniform", min = 20.0, max = 70.0 }
downhill_azimuth_deg = { dist = "uniform", min = 0.0, max = 360.0 }
"#,
    set_down_lines!("0.0", "0.0"),
    r#"[initial]
attitude_reference = "surface"
# 1 micrometre above the surface: the gear meets it at 0.2 mm/s, set down, not dropped
# (a drop of 1 mm already tips landers 1-2 deg below the static limit by the friction
# impulse at the footpads).
clearance_m = 1.0e-6
[simulation]
t_max_s = 60.0
"#
);

/// `atan(r / h)` of the default gear (4 legs at 0.6 m, the first at 45 deg, CG 0.428936 m
/// above the footpads) for a downhill azimuth relative to the lander, deg.
fn static_limit_deg(azimuth_deg: f64) -> f64 {
    // Edge normals at 0, 90, 180, 270 deg; the edge is R cos(45 deg) from the centre.
    let off = (azimuth_deg.rem_euclid(90.0)).min(90.0 - azimuth_deg.rem_euclid(90.0));
    let r = 0.6 * std::f64::consts::FRAC_PI_4.cos() / off.to_radians().cos();
    (r / 0.428936).atan().to_degrees()
}

/// Sweeps `samples` of `scenario` into `out` and reports on it: the sweep's run and the
/// report.
fn sweep_and_report(dir: &TempDir, scenario: &str, samples: &str, out: &str) -> (Run, String) {
    let name = format!("{out}.toml");
    dir.write(&name, scenario);
    let sweep = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            &name,
            "--samples",
            samples,
            "--quiet",
            "--out",
            out,
        ],
    );
    assert_eq!(sweep.code, Some(0), "{sweep}");
    let run = touchdown(dir.path(), &["report", out]);
    assert_eq!(run.code, Some(0), "{run}");
    (sweep, run.stdout)
}

#[test]
fn report_counts_and_allowable_slopes_of_gentle_landings() {
    let dir = TempDir::new("report");
    let (sweep, report) = sweep_and_report(&dir, GENTLE, "4000", "g.arrow");

    // The outcome rows carry the counts of the sweep's closing summary.
    for line in sweep
        .stdout
        .lines()
        .filter(|l| l.ends_with('%') && l.starts_with("  "))
    {
        let w: Vec<&str> = line.split_whitespace().collect();
        let row = format!("| {} | {} |", w[0], w[1]);
        assert!(
            report.contains(&row),
            "no row {row:?} in the report:\n{report}"
        );
    }

    // Every sample stands or falls as the static limit says, away from the limit (within
    // 0.5 deg of it the settling of the gear decides), ...
    let (slopes, azimuths, stable) = read_samples(&dir.join("g.arrow"));
    let mut wrong = Vec::new();
    for ((slope, azimuth), stable) in slopes.iter().zip(&azimuths).zip(&stable) {
        let limit = static_limit_deg(*azimuth);
        if (slope - limit).abs() > 0.5 && (*slope < limit) != *stable {
            wrong.push(format!(
                "slope {slope:.2} at {azimuth:.1} deg (limit {limit:.2}): stable {stable}"
            ));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} samples against the static limit:\n{}",
        wrong.len(),
        wrong.join("\n")
    );

    // ... and the report's allowable slope per sector is the one the static limit gives
    // for the same samples, within what the 0.5 deg band at the limit leaves open.
    let mut sectors = 0;
    for line in report
        .lines()
        .filter(|l| l.contains("–") && l.ends_with(" deg |"))
    {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let from: f64 = cells[1].split('–').next().unwrap().parse().unwrap();
        let allowable: f64 = cells[4]
            .trim_end_matches(" deg")
            .parse()
            .unwrap_or_else(|_| {
                panic!("no allowable slope in {line:?}:\n{report}");
            });
        // The allowable slope only grows when a sample turns stable, and every sample
        // outside the 0.5 deg band stands or falls as the static limit says (checked above):
        // so it lies between the allowable slopes of samples stable below limit - 0.5 and of
        // samples stable below limit + 0.5.
        let allowable_with = |band: f64| {
            let mut predicted: Vec<(f64, bool)> = slopes
                .iter()
                .zip(&azimuths)
                .filter(|(_, a)| (from..from + 45.0).contains(*a))
                .map(|(s, a)| (*s, *s < static_limit_deg(*a) + band))
                .collect();
            touchdown::stats::allowable_slope(&mut predicted)
                .slope_deg()
                .unwrap()
        };
        let (low, high) = (allowable_with(-0.5), allowable_with(0.5));
        // The report prints one decimal.
        assert!(
            low - 0.05 <= allowable && allowable <= high + 0.05,
            "sector from {from} deg: allowable {allowable} deg, the static limit gives \
             {low:.2} to {high:.2} deg"
        );
        sectors += 1;
    }
    assert_eq!(sectors, 8, "eight sectors in:\n{report}");
}

/// Slope, downhill azimuth relative to the lander, and whether it ended stable, per sample.
fn read_samples(path: &std::path::Path) -> (Vec<f64>, Vec<f64>, Vec<bool>) {
    use arrow_array::{Array, Float64Array};
    let reader =
        arrow_ipc::reader::FileReader::try_new(std::fs::File::open(path).unwrap(), None).unwrap();
    let (mut slopes, mut azimuths, mut stable) = (Vec::new(), Vec::new(), Vec::new());
    for b in reader {
        let b = b.unwrap();
        let f = |name: &str| {
            b.column_by_name(name)
                .unwrap()
                .as_any()
                .downcast_ref::<Float64Array>()
                .unwrap()
                .clone()
        };
        let (slope, azimuth, yaw) = (f("slope_deg"), f("downhill_azimuth_deg"), f("yaw_deg"));
        let outcome = b.column_by_name("outcome").unwrap();
        let outcome = crate::common::texts(outcome.as_ref());
        for (i, o) in outcome.iter().enumerate() {
            slopes.push(slope.value(i));
            azimuths.push((azimuth.value(i) - yaw.value(i)).rem_euclid(360.0));
            stable.push(o == "stable");
        }
    }
    (slopes, azimuths, stable)
}

#[test]
fn report_tells_too_few_samples_from_no_safe_slope() {
    let dir = TempDir::new("report-few");
    // 300 samples: some 37 per sector, too few for any allowable slope.
    let (_, report) = sweep_and_report(&dir, GENTLE, "300", "few.arrow");
    let rows: Vec<&str> = report.lines().filter(|l| l.contains(" deg | ")).collect();
    assert_eq!(rows.len(), 8, "{}", report);
    for row in &rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[4], format!("too few samples ({})", cells[2]), "{row}");
        assert_eq!(cells[5], "–", "{row}");
    }

    // Landers on 60-70 deg all tip: with enough samples, there is no safe slope, and the
    // 95 % interval says below which slope the true one may still lie.
    let steep = GENTLE.replace("min = 20.0, max = 70.0", "min = 60.0, max = 70.0");
    let (_, report) = sweep_and_report(&dir, &steep, "1600", "steep.arrow");
    let rows: Vec<&str> = report.lines().filter(|l| l.contains(" deg | ")).collect();
    assert_eq!(rows.len(), 8, "{}", report);
    for row in &rows {
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(cells[3], "0.0 %", "{row}");
        assert_eq!(cells[4], "no slope with ≥ 99 % stable", "{row}");
        assert!(
            cells[5].starts_with("0.0–") && cells[5].ends_with(" deg"),
            "{row}"
        );
    }
    // How to see one of them in detail, and why the damper columns are 0.
    assert!(
        report.contains("`touchdown trace --sweep steep.arrow --sample I`"),
        "{}",
        report
    );
    assert!(
        report.contains("The dampers are off in this scenario"),
        "{}",
        report
    );
}

#[test]
fn report_refuses_what_is_not_a_sweep() {
    let dir = TempDir::new("report-bad");
    dir.write("s.toml", "[simulation]\nt_max_s = 5.0\n");
    let t = touchdown(
        dir.path(),
        &["trace", "--scenario", "s.toml", "--out", "t.arrow"],
    );
    assert_eq!(t.code, Some(0), "{t}");
    for (args, expect) in [
        (vec!["report", "t.arrow"], "t.arrow is not a sweep file"),
        (
            vec!["report", "s.toml"],
            "s.toml is neither an Arrow IPC file nor a Parquet file",
        ),
        (vec!["report", "missing.arrow"], "cannot read missing.arrow"),
    ] {
        let run = touchdown(dir.path(), &args);
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(expect), "{run}");
        // A report reads a sweep, not a shard.
        assert!(!run.stderr.contains("shard"), "{run}");
    }
}

/// With thrusters, the report gives the propellant and firings; its figures are those of
/// the file's own columns (recomputed here from them), and a passive sweep's report has no
/// such section.
#[test]
fn report_gives_propellant_statistics_of_a_sweep_with_thrusters() {
    use arrow_array::{Array, Float64Array, UInt32Array};
    let dir = TempDir::new("report_propellant");
    let scenario = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml"),
    )
    .unwrap();
    let (_, report) = sweep_and_report(&dir, &scenario, "160", "h.arrow");
    let file = std::fs::File::open(dir.join("h.arrow")).unwrap();
    let (mut propellant, mut fired) = (Vec::new(), 0);
    let mut by_outcome: std::collections::BTreeMap<String, (f64, u64)> = Default::default();
    for b in arrow_ipc::reader::FileReader::try_new(file, None).unwrap() {
        let b = b.unwrap();
        let col = |n: &str| b.column_by_name(n).unwrap().clone();
        let p = col("propellant_kg");
        let p = p.as_any().downcast_ref::<Float64Array>().unwrap();
        let f = col("firings");
        let f = f.as_any().downcast_ref::<UInt32Array>().unwrap();
        let o = col("outcome");
        let o = crate::common::texts(o.as_ref());
        for (i, o) in o.into_iter().enumerate() {
            propellant.push(p.value(i));
            fired += usize::from(f.value(i) > 0);
            let e = by_outcome.entry(o).or_default();
            e.0 += p.value(i);
            e.1 += 1;
        }
    }
    let total: f64 = propellant.iter().sum();
    let largest = propellant.iter().copied().fold(0.0, f64::max);
    assert!(largest > 0.0, "hold-down.toml burns propellant");
    assert!(
        report.contains(&format!(
            "{fired} of 160 samples fired a thruster; {total:.4} kg of propellant"
        )),
        "{report}"
    );
    let mean = total / 160.0;
    assert!(
        report.lines().any(
            |l| l.starts_with(&format!("| propellant used (kg) | {mean:.4} |"))
                && l.ends_with(&format!("| {largest:.4} |"))
        ),
        "{report}"
    );
    for (outcome, (kg, k)) in &by_outcome {
        let row = format!("| {outcome} | {k} | {:.4} |", kg / *k as f64);
        assert!(report.contains(&row), "no row {row:?} in\n{report}");
    }
    let (_, passive) = sweep_and_report(&dir, "", "40", "p.arrow");
    assert!(!passive.contains("Propellant"), "{passive}");
}
