//! `touchdown envelope`: its cells count every sample that touched by outcome, its
//! boundary is `report`'s allowable-slope rule along x (computed here again from the file's
//! columns), it takes any two numeric columns, marks the cells where samples broke a limit
//! (a `limits_broken` column, in a file made here), and refuses bad input with exit code 2.

use crate::common::{SHORT, TempDir, touchdown};
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Field, Schema};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// Landers released from 0-2 m with a sideways velocity of up to 1 m/s, attitude along the
/// normal, on slopes of 0-10 deg: their touchdown speeds fill the plane, and the slow ones
/// stand (a 99 %-stable boundary exists at low normal speed).
const PLANE: &str = r#"
[inputs]
slope_deg = { dist = "uniform", min = 0.0, max = 10.0 }
release_height_m = { dist = "uniform", min = 0.0, max = 2.0 }
velocity_error_x_m_s = { dist = "uniform", min = -1.0, max = 1.0 }
[initial]
attitude_reference = "surface"
[simulation]
t_max_s = 60.0
"#;

/// Sweeps `samples` of `scenario` into `dir/out`.
fn sweep(dir: &TempDir, scenario: &str, samples: &str, out: &str) {
    dir.write("s.toml", scenario);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--samples",
            samples,
            "--quiet",
            "--out",
            out,
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
}

/// Runs `touchdown envelope ARGS` in `dir`, which must succeed; its stdout.
fn envelope(dir: &TempDir, args: &[&str]) -> String {
    let mut all = vec!["envelope"];
    all.extend(args);
    let run = touchdown(dir.path(), &all);
    run.assert_ok();
    run.stdout
}

/// The rows of a CSV file as maps from the header's names.
fn csv_rows(path: &Path) -> Vec<HashMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

/// A number of a CSV row.
fn num(row: &HashMap<String, String>, name: &str) -> f64 {
    row[name]
        .parse()
        .unwrap_or_else(|_| panic!("{name}: {row:?}"))
}

/// The columns of an Arrow file: numbers as `f64` (null as NaN; whole numbers too), text
/// as strings.
struct Columns {
    numbers: HashMap<String, Vec<f64>>,
    texts: HashMap<String, Vec<String>>,
}

fn columns(path: &Path) -> Columns {
    use arrow_array::cast::AsArray;
    use arrow_array::types::{Float64Type, UInt32Type};
    let reader =
        arrow_ipc::reader::FileReader::try_new(std::fs::File::open(path).unwrap(), None).unwrap();
    let mut c = Columns {
        numbers: HashMap::new(),
        texts: HashMap::new(),
    };
    for b in reader {
        let b = b.unwrap();
        for (f, a) in b.schema().fields().iter().zip(b.columns()) {
            let name = f.name().clone();
            match a.data_type() {
                DataType::Float64 => c.numbers.entry(name).or_default().extend(
                    a.as_primitive::<Float64Type>()
                        .iter()
                        .map(|v| v.unwrap_or(f64::NAN)),
                ),
                DataType::UInt32 => c.numbers.entry(name).or_default().extend(
                    a.as_primitive::<UInt32Type>()
                        .iter()
                        .map(|v| v.map_or(f64::NAN, f64::from)),
                ),
                DataType::Utf8 | DataType::Dictionary(..) => c
                    .texts
                    .entry(name)
                    .or_default()
                    .extend(crate::common::texts(a.as_ref())),
                _ => {}
            }
        }
    }
    c
}

/// Whether the PNG at `path` has a pixel of colour `rgb`.
fn has_colour(path: &Path, rgb: [u8; 3]) -> bool {
    let img = image::open(path).unwrap().to_rgb8();
    img.pixels().any(|p| p.0 == rgb)
}

/// The magenta of the limit marks (`plot::envelope`'s `LIMIT`).
const LIMIT: [u8; 3] = [200, 0, 200];

#[test]
fn cells_count_every_sample_that_touched_by_outcome() {
    let dir = TempDir::new("envelope-counts");
    sweep(&dir, SHORT, "2000", "d.arrow");
    sweep(&dir, SHORT, "2000", "d.parquet");
    let md = envelope(&dir, &["d.arrow"]);
    envelope(&dir, &["d.parquet", "--out-dir", "pq"]);
    // Arrow and Parquet give the same table.
    assert_eq!(
        std::fs::read_to_string(dir.join("d-envelope.csv")).unwrap(),
        std::fs::read_to_string(dir.join("pq/d-envelope.csv")).unwrap()
    );

    let c = columns(&dir.join("d.arrow"));
    let touched: Vec<bool> = c.numbers["touchdown_normal_speed_m_s"]
        .iter()
        .map(|v| !v.is_nan())
        .collect();
    let outcomes = &c.texts["outcome"];
    let rows = csv_rows(&dir.join("d-envelope.csv"));
    for o in [
        "stable", "tipped", "sliding", "bouncing", "diverged", "held",
    ] {
        let expected = outcomes
            .iter()
            .zip(&touched)
            .filter(|(x, t)| x.as_str() == o && **t)
            .count();
        let counted: f64 = rows.iter().map(|r| num(r, o)).sum();
        assert_eq!(counted as usize, expected, "{o}");
    }
    let total: f64 = rows.iter().map(|r| num(r, "samples")).sum();
    let n_touched = touched.iter().filter(|t| **t).count();
    assert_eq!(total as usize, n_touched);
    let never = 2000 - n_touched;
    assert!(
        md.starts_with(&format!(
            "# touchdown envelope: d.arrow\n\n2000 samples, seed 1: {n_touched} in the panels"
        )),
        "{md}"
    );
    if never > 0 {
        assert!(md.contains(&format!("; {never} never touched")), "{md}");
    }
    // The default sweep's slopes (0-45 deg): three bands of 15 deg, each in the table.
    for band in [
        "## slope 0–15 deg",
        "## slope 15–30 deg",
        "## slope 30–45 deg",
    ] {
        assert!(md.contains(band), "{band}:\n{md}");
    }
    assert_eq!(rows.len(), 3 * 12 * 10);
    // No limits in this sweep: no limit column, no marks.
    assert!(rows.iter().all(|r| r["limits_broken"].is_empty()));
    assert!(!has_colour(&dir.join("d-envelope.png"), LIMIT));
}

/// `report`'s rule, written out again: the largest x at or below which at least 99 % of
/// `samples` are stable, counting only x with at least 100 samples at or below them; its
/// 95 % interval from the largest x whose stable share's Wilson interval lies at or above
/// 99 % (0 if none) to the largest whose interval reaches 99 %.
fn allowable(mut samples: Vec<(f64, bool)>) -> Option<(f64, f64, f64)> {
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let z: f64 = 1.959_963_984_540_054;
    let (mut best, mut low, mut high) = (None, 0.0, None);
    let mut stable = 0usize;
    for (i, (x, ok)) in samples.iter().enumerate() {
        stable += usize::from(*ok);
        let n = i + 1;
        if samples.get(n).is_some_and(|next| next.0 <= *x) || n < 100 {
            continue;
        }
        let (p, nf) = (stable as f64 / n as f64, n as f64);
        let centre = (p + z * z / (2.0 * nf)) / (1.0 + z * z / nf);
        let half = z / (1.0 + z * z / nf) * (p * (1.0 - p) / nf + z * z / (4.0 * nf * nf)).sqrt();
        let lo = if stable == 0 { 0.0 } else { centre - half };
        let hi = if stable == n { 1.0 } else { centre + half };
        if stable as f64 >= 0.99 * nf {
            best = Some(*x);
        }
        if lo >= 0.99 {
            low = *x;
        }
        if hi >= 0.99 {
            high = Some(*x);
        }
    }
    best.map(|b| (b, low, high.unwrap_or(b)))
}

#[test]
fn the_boundary_is_the_allowable_slope_rule_along_x() {
    let dir = TempDir::new("envelope-boundary");
    sweep(&dir, PLANE, "3000", "p.arrow");
    let md = envelope(&dir, &["p.arrow", "--bins", "4,3", "--slope-bands", "0,10"]);
    let c = columns(&dir.join("p.arrow"));
    let (x, y) = (
        &c.numbers["touchdown_tangential_speed_m_s"],
        &c.numbers["touchdown_normal_speed_m_s"],
    );
    let stable: Vec<bool> = c.texts["outcome"].iter().map(|o| o == "stable").collect();
    let rows = csv_rows(&dir.join("p-envelope.csv"));
    let y_top = rows
        .iter()
        .map(|r| num(r, "y_max"))
        .fold(f64::MIN, f64::max);
    let x_span = rows
        .iter()
        .map(|r| num(r, "x_max"))
        .fold(f64::MIN, f64::max)
        - rows
            .iter()
            .map(|r| num(r, "x_min"))
            .fold(f64::MAX, f64::min);
    let mut checked = 0;
    for r in rows.iter().filter(|r| r["x_min"] == rows[0]["x_min"]) {
        // The row's samples: y in [y_min, y_max), the top row closed.
        let (lo, hi) = (num(r, "y_min"), num(r, "y_max"));
        let samples: Vec<(f64, bool)> = (0..x.len())
            .filter(|&i| y[i] >= lo && (y[i] < hi || (hi == y_top && y[i] <= hi)))
            .map(|i| (x[i], stable[i]))
            .collect();
        assert_eq!(samples.len() as f64, num(r, "row_samples"), "{r:?}");
        match allowable(samples) {
            Some((b, l, h)) => {
                assert_eq!(num(r, "row_boundary_x"), b, "{r:?}");
                assert_eq!(num(r, "row_boundary_low_x"), l, "{r:?}");
                assert_eq!(num(r, "row_boundary_high_x"), h, "{r:?}");
                // The summary shows it, to three digits of the x axis's span.
                let d = (2.0 - x_span.log10().floor()).clamp(0.0, 9.0) as usize;
                assert!(
                    md.contains(&format!("| {b:.d$} | {l:.d$}–{h:.d$} |")),
                    "{md}"
                );
                checked += 1;
            }
            None => assert!(r["row_boundary_x"].is_empty(), "{r:?}"),
        }
    }
    assert!(checked >= 1, "no row with a boundary:\n{md}");
}

#[test]
fn any_two_numeric_columns_span_the_plane() {
    let dir = TempDir::new("envelope-columns");
    sweep(&dir, SHORT, "1000", "d.arrow");
    // A Float64 input against a UInt32 result.
    let md = envelope(
        &dir,
        &[
            "d.arrow",
            "--x",
            "velocity_error_x_m_s",
            "--y",
            "bounces",
            "--bins",
            "5,4",
        ],
    );
    assert!(
        md.contains("x: `velocity_error_x_m_s (m/s)`, 5 bins")
            && md.contains("y: `bounces`, 4 bins"),
        "{md}"
    );
    let c = columns(&dir.join("d.arrow"));
    let rows = csv_rows(&dir.join("d-envelope.csv"));
    // Every row names the columns its x and y ranges are of, after the columns that were
    // there before (a reader by place reads those as before).
    let header = std::fs::read_to_string(dir.join("d-envelope.csv")).unwrap();
    assert!(
        header
            .lines()
            .next()
            .unwrap()
            .ends_with(",row_boundary_high_x,x_column,y_column"),
        "{header}"
    );
    for r in &rows {
        assert_eq!(
            (r["x_column"].as_str(), r["y_column"].as_str()),
            ("velocity_error_x_m_s", "bounces")
        );
    }
    let touched: Vec<usize> = (0..1000)
        .filter(|&i| !c.numbers["touchdown_normal_speed_m_s"][i].is_nan())
        .collect();
    let vx = &c.numbers["velocity_error_x_m_s"];
    let least = touched.iter().map(|&i| vx[i]).fold(f64::MAX, f64::min);
    let most = touched.iter().map(|&i| vx[i]).fold(f64::MIN, f64::max);
    assert_eq!(num(&rows[0], "x_min"), least);
    assert_eq!(num(&rows[4], "x_max"), most);
    let total: f64 = rows.iter().map(|r| num(r, "samples")).sum();
    assert_eq!(total as usize, touched.len());
    // Each cell's samples are those in its slope band and ranges (half-open; the last
    // band and bin closed).
    let (bounces, slope) = (&c.numbers["bounces"], &c.numbers["slope_deg"]);
    let last = |name: &str| rows.iter().map(|r| num(r, name)).fold(f64::MIN, f64::max);
    let (x_top, y_top, s_top) = (last("x_max"), last("y_max"), last("slope_max_deg"));
    for r in &rows {
        let inside = |v: f64, lo: &str, hi: &str, top: f64| {
            let (lo, hi) = (num(r, lo), num(r, hi));
            v >= lo && (v < hi || (hi == top && v <= hi))
        };
        let n = touched
            .iter()
            .filter(|&&i| {
                inside(slope[i], "slope_min_deg", "slope_max_deg", s_top)
                    && inside(vx[i], "x_min", "x_max", x_top)
                    && inside(bounces[i], "y_min", "y_max", y_top)
            })
            .count();
        assert_eq!(n as f64, num(r, "samples"), "{r:?}");
    }
    assert_eq!(x_top, most);
}

/// Writes a sweep-like Arrow file: the columns the envelope reads, a `limits_broken` column
/// if `limits`, and the metadata of a sweep without its scenario. Row `i` of 400 lies on a
/// 20 x 20 grid of speeds (0 to 0.95 m/s); the landers with the two speeds summing to 1
/// or more tip; every 37th never touched; those slow along and fast towards the surface
/// broke a limit or two.
fn made_sweep(path: &Path, limits: bool) -> Vec<(f64, f64, bool, String)> {
    let rows: Vec<(f64, f64, bool, String)> = (0..400)
        .map(|i| {
            let (x, y) = (f64::from(i % 20) * 0.05, f64::from(i / 20) * 0.05);
            let broke = match (x < 0.25 && y >= 0.8, i % 3) {
                (false, _) => "",
                (true, 0) => "axial_force,stroke_margin",
                (true, _) => "axial_force",
            };
            (x, y, i % 37 != 0, broke.to_string())
        })
        .collect();
    let unit = |u: &str| HashMap::from([("unit".to_string(), u.to_string())]);
    let mut fields = vec![
        Field::new("slope_deg", DataType::Float64, false).with_metadata(unit("deg")),
        Field::new("outcome", DataType::Utf8, false),
        Field::new("touchdown_normal_speed_m_s", DataType::Float64, true)
            .with_metadata(unit("m/s")),
        Field::new("touchdown_tangential_speed_m_s", DataType::Float64, true)
            .with_metadata(unit("m/s")),
    ];
    let mut arrays: Vec<ArrayRef> = vec![
        Arc::new(Float64Array::from(vec![5.0; 400])),
        Arc::new(StringArray::from_iter_values(
            rows.iter()
                .map(|r| if r.0 + r.1 >= 1.0 { "tipped" } else { "stable" }),
        )),
        Arc::new(Float64Array::from_iter(
            rows.iter().map(|r| r.2.then_some(r.1)),
        )),
        Arc::new(Float64Array::from_iter(
            rows.iter().map(|r| r.2.then_some(r.0)),
        )),
    ];
    if limits {
        fields.push(Field::new("limits_broken", DataType::Utf8, false));
        arrays.push(Arc::new(StringArray::from_iter_values(
            rows.iter().map(|r| r.3.as_str()),
        )));
    }
    let meta = HashMap::from([
        ("touchdown.kind".to_string(), "sweep".to_string()),
        ("touchdown.seed".to_string(), "7".to_string()),
    ]);
    let schema = Arc::new(Schema::new(fields).with_metadata(meta));
    let batch = RecordBatch::try_new(schema.clone(), arrays).unwrap();
    let mut w =
        arrow_ipc::writer::FileWriter::try_new(std::fs::File::create(path).unwrap(), &schema)
            .unwrap();
    w.write(&batch).unwrap();
    w.finish().unwrap();
    rows
}

#[test]
fn cells_where_samples_broke_a_limit_are_marked_and_counted() {
    let dir = TempDir::new("envelope-limits");
    let rows = made_sweep(&dir.join("m.arrow"), true);
    let md = envelope(&dir, &["m.arrow", "--bins", "4,4"]);
    let touched: Vec<&(f64, f64, bool, String)> = rows.iter().filter(|r| r.2).collect();
    let broke = touched.iter().filter(|r| !r.3.is_empty()).count();
    assert!(broke > 0);
    assert!(
        md.contains(&format!(
            "400 samples, seed 7: {} in the panels; {} never touched",
            touched.len(),
            400 - touched.len()
        )),
        "{md}"
    );
    assert!(md.contains(&format!("{broke} broke a limit")), "{md}");
    // Per cell: the samples in its ranges that broke a limit.
    let cells = csv_rows(&dir.join("m-envelope.csv"));
    assert_eq!(cells.len(), 16);
    let last = |name: &str| cells.iter().map(|r| num(r, name)).fold(f64::MIN, f64::max);
    let (x_top, y_top) = (last("x_max"), last("y_max"));
    for c in &cells {
        let inside = |v: f64, lo: &str, hi: &str, top: f64| {
            let (lo, hi) = (num(c, lo), num(c, hi));
            v >= lo && (v < hi || (hi == top && v <= hi))
        };
        let expected = touched
            .iter()
            .filter(|r| {
                !r.3.is_empty()
                    && inside(r.0, "x_min", "x_max", x_top)
                    && inside(r.1, "y_min", "y_max", y_top)
            })
            .count();
        assert_eq!(num(c, "limits_broken") as usize, expected, "{c:?}");
    }
    let png = dir.join("m-envelope.png");
    assert!(
        has_colour(&png, LIMIT),
        "no limit marks in {}",
        png.display()
    );
    // The same file without the column: no marks, no counts.
    made_sweep(&dir.join("n.arrow"), false);
    let md = envelope(&dir, &["n.arrow", "--bins", "4,4"]);
    assert!(!md.contains("broke a limit"), "{md}");
    assert!(!has_colour(&dir.join("n-envelope.png"), LIMIT));
}

#[test]
fn bad_input_is_refused_naming_it() {
    let dir = TempDir::new("envelope-bad");
    made_sweep(&dir.join("m.arrow"), true);
    dir.write("notes.txt", "not a sweep\n");
    dir.write("file", "");
    let cases: &[(&[&str], &str)] = &[
        (
            &["m.arrow", "--x", "nope"],
            "--x nope: m.arrow has no column nope",
        ),
        (
            &["m.arrow", "--y", "outcome"],
            "--y outcome: the column outcome of m.arrow is not numeric",
        ),
        (
            &["notes.txt"],
            "notes.txt is neither an Arrow IPC file nor a Parquet file",
        ),
        (&["missing.arrow"], "cannot read missing.arrow"),
        (&["m.arrow", "--bins", "0,5"], "--bins"),
        (&["m.arrow", "--bins", "12"], "--bins"),
        (
            &["m.arrow", "--slope-bands", "10,5"],
            "--slope-bands 10,5: the edges must increase",
        ),
        (
            &["m.arrow", "--slope-bands", "5"],
            "--slope-bands 5: at least two edges",
        ),
        (
            &["m.arrow", "--slope-bands", "0,95"],
            "--slope-bands 0,95: 95 is not a slope",
        ),
        (&["m.arrow", "--slope-bands", "0,x"], "--slope-bands"),
        (
            &["m.arrow", "--azimuth"],
            "--azimuth: m.arrow has no scenario",
        ),
        (
            &["m.arrow", "--out-dir", "file"],
            "--out-dir file: a file, not a folder",
        ),
    ];
    let mut problems = Vec::new();
    for (args, expect) in cases {
        let before = dir.entries();
        let mut all = vec!["envelope"];
        all.extend(*args);
        let run = touchdown(dir.path(), &all);
        if run.code != Some(2)
            || !run.stderr.contains(expect)
            || run.stderr.contains("panicked")
            || !run.stdout.is_empty()
            || dir.entries() != before
        {
            problems.push(format!(
                "expected exit code 2 and {expect:?}, no files:\n{run}"
            ));
        }
    }
    // A trace file is not a sweep.
    dir.write("t.toml", SHORT);
    let trace = touchdown(
        dir.path(),
        &[
            "trace",
            "--scenario",
            "t.toml",
            "--out",
            "t.arrow",
            "--every",
            "1000",
        ],
    );
    assert_eq!(trace.code, Some(0), "{trace}");
    let run = touchdown(dir.path(), &["envelope", "t.arrow"]);
    if run.code != Some(2)
        || !run
            .stderr
            .contains("t.arrow is not a sweep file of touchdown")
    {
        problems.push(format!("a trace file:\n{run}"));
    }
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

#[test]
fn azimuth_splits_each_band_into_leg_and_side_downhill() {
    let dir = TempDir::new("envelope-azimuth");
    sweep(&dir, SHORT, "1000", "d.arrow");
    let md = envelope(&dir, &["d.arrow", "--azimuth", "--bins", "3,2"]);
    for title in [
        "## slope 0–15 deg, leg-downhill",
        "## slope 0–15 deg, side-downhill",
        "## slope 30–45 deg, side-downhill",
    ] {
        assert!(md.contains(title), "{title}:\n{md}");
    }
    // The default gear's legs point at 45, 135, 225 and 315 deg from X_B: a leg is
    // downhill where the downhill azimuth relative to the lander is within 22.5 deg of one.
    let c = columns(&dir.join("d.arrow"));
    let (azimuth, yaw, slope, normal) = (
        &c.numbers["downhill_azimuth_deg"],
        &c.numbers["yaw_deg"],
        &c.numbers["slope_deg"],
        &c.numbers["touchdown_normal_speed_m_s"],
    );
    let rows = csv_rows(&dir.join("d-envelope.csv"));
    for band in [(0.0, 15.0), (15.0, 30.0), (30.0, 45.0)] {
        for facing in ["leg-downhill", "side-downhill"] {
            let expected = (0..1000)
                .filter(|&i| {
                    let relative = (azimuth[i] - yaw[i]).rem_euclid(360.0);
                    let off = (relative - 45.0).rem_euclid(90.0);
                    let leg = off.min(90.0 - off) <= 22.5;
                    !normal[i].is_nan()
                        && slope[i] >= band.0
                        && (slope[i] < band.1 || band.1 == 45.0)
                        && leg == (facing == "leg-downhill")
                })
                .count();
            let counted: f64 = rows
                .iter()
                .filter(|r| r["facing"] == facing && num(r, "slope_min_deg") == band.0)
                .map(|r| num(r, "samples"))
                .sum();
            assert_eq!(counted as usize, expected, "{band:?} {facing}");
            // Half the azimuths face a leg: each facing holds a fair share of the band.
            assert!(expected > 60, "{band:?} {facing}: {expected}");
        }
    }
}

#[test]
fn panels_too_many_for_one_command_are_refused_not_aborted() {
    let dir = TempDir::new("envelope-size");
    sweep(&dir, SHORT, "300", "m.arrow");
    let bands: Vec<String> = (0..=45).map(|d| d.to_string()).collect();
    let before = dir.entries();
    // Run under an address-space limit of 2 GB, as on a smaller machine, where an
    // allocation past it aborts: 90 panels of a million cells are refused before any.
    let run = std::process::Command::new("sh")
        .args([
            "-c",
            &format!(
                "ulimit -v 2000000; exec {} envelope m.arrow --bins 1000,1000 --slope-bands {} \
                 --azimuth",
                crate::common::BIN,
                bands.join(",")
            ),
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(
            "--bins 1000,1000 with --slope-bands of 45 bands and --azimuth: 90 panels of 1000 x \
             1000 cells, 90000000 cells in all (about"
        ) && stderr.contains("at most 1,000,000 cells in all panels together"),
        "{stderr}"
    );
    assert_eq!(dir.entries(), before);
    // A picture of too many panels, each of one cell.
    let bands: Vec<String> = (0..=900)
        .map(|d| format!("{}", f64::from(d) / 10.0))
        .collect();
    let run = touchdown(
        dir.path(),
        &[
            "envelope",
            "m.arrow",
            "--bins",
            "1,1",
            "--slope-bands",
            &bands.join(","),
            "--azimuth",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(
        run.stderr
            .contains("1800 panels of 1 x 1 cells: a picture of")
            && run.stderr.contains("pixels a picture may have"),
        "{run}"
    );
    assert_eq!(dir.entries(), before);
}

/// A column with no value in any sample (the stroke margin of rigid legs: null without
/// dampers) is refused naming it, not drawn as an empty picture.
#[test]
fn a_column_without_values_is_refused_not_drawn_empty() {
    let dir = TempDir::new("envelope-empty-column");
    sweep(&dir, SHORT, "100", "s.arrow");
    for (flag, expect) in [
        ("--x", "--x leg1_stroke_margin_m: the column has no value"),
        ("--y", "--y leg1_stroke_margin_m: the column has no value"),
    ] {
        let run = touchdown(
            dir.path(),
            &["envelope", "s.arrow", flag, "leg1_stroke_margin_m"],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(
            run.stderr.contains(expect) && run.stderr.contains("samples of s.arrow that touched"),
            "{run}"
        );
        assert!(!dir.join("s-envelope.png").exists(), "{run}");
    }
}
