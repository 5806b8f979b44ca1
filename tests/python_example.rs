//! The Python side of touchdown's files, as users meet it: the example script
//! `examples/python/stability.py` agrees with `touchdown report` on real sweeps (Arrow and
//! Parquet) and draws its map, and pyarrow, pandas and polars read the values the CLI
//! printed from sweep and trace files (`tests/python/check_printed_values.py`).
//!
//! Like the other Python tests, these fail when Python or its packages are missing, unless
//! `TOUCHDOWN_SKIP_PYTHON=1` (then they are skipped with a note).

use crate::common::{
    SHORT, THREE_LEGS, TempDir, python, python_readers_available, read_bytes, run_python_check,
    touchdown,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Gentle landings of the default gear on slopes up to 60 deg (past its static limit, 44.7
/// to 54.4 deg) at any yaw: friction high enough that little slides, no attitude or rate
/// errors, drops of at most 1 cm, so every sector has an allowable slope near the limit.
const STEEP: &str = r#"
[surface]
friction_coefficient = 1.5

[inputs]
slope_deg = { dist = "uniform", min = 0.0, max = 60.0 }
release_height_m = { dist = "uniform", min = 0.0, max = 0.01 }
yaw_deg = { dist = "uniform", min = 0.0, max = 360.0 }
velocity_error_x_m_s = 0.0
velocity_error_y_m_s = 0.0
velocity_error_z_m_s = 0.0
roll_deg = 0.0
pitch_deg = 0.0
rate_x_deg_s = 0.0
rate_y_deg_s = 0.0
rate_z_deg_s = 0.0

[initial]
attitude_reference = "surface"

[simulation]
t_max_s = 20.0
"#;

const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";

fn example_script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/python/stability.py")
}

/// Runs `python3 ARGS` in `dir`; panics with its output unless it exits 0. Returns stdout.
fn run_python(dir: &Path, args: &[&std::ffi::OsStr]) -> String {
    let o = Command::new(python())
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", python()));
    let stdout = String::from_utf8(o.stdout).expect("stdout is UTF-8");
    assert!(
        o.status.success(),
        "`{} {args:?}` failed ({:?}):\n--- stdout ---\n{stdout}--- stderr ---\n{}",
        python(),
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    stdout
}

/// Runs `touchdown sweep ARGS` in `dir`; panics unless it exits 0. Returns the outcome counts
/// of its closing summary.
fn sweep(dir: &TempDir, args: &[&str]) -> BTreeMap<String, String> {
    let mut all = vec!["sweep", "--quiet"];
    all.extend(args);
    let run = touchdown(dir.path(), &all);
    assert_eq!(run.code, Some(0), "expected success of {run}");
    // "outcomes" then "  stable  1183   29.57 %" lines.
    let counts: BTreeMap<String, String> = run
        .stdout
        .lines()
        .skip_while(|l| *l != "outcomes")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (w[0].to_string(), w[1].to_string())
        })
        .collect();
    assert_eq!(counts.len(), 5, "cannot read the outcomes of {run}");
    counts
}

/// The rows of the first Markdown table after the line `heading`, as column -> cell.
fn table(text: &str, heading: &str) -> Vec<BTreeMap<String, String>> {
    let cells = |l: &str| -> Vec<String> {
        l.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut lines = text
        .lines()
        .skip_while(|l| l.trim() != heading)
        .skip(1)
        .skip_while(|l| !l.starts_with('|'));
    let header = cells(
        lines
            .next()
            .unwrap_or_else(|| panic!("no table under {heading:?} in:\n{text}")),
    );
    let separator = lines.next().unwrap_or_default();
    assert!(
        separator.starts_with("|---"),
        "no table under {heading:?} in:\n{text}"
    );
    lines
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let row = cells(l);
            assert_eq!(row.len(), header.len(), "row {l:?} under {heading:?}");
            header.iter().cloned().zip(row).collect()
        })
        .collect()
}

/// The columns `names` of every row.
fn columns(rows: &[BTreeMap<String, String>], names: &[&str]) -> Vec<Vec<String>> {
    rows.iter()
        .map(|r| {
            names
                .iter()
                .map(|n| {
                    r.get(*n)
                        .unwrap_or_else(|| panic!("no column {n:?} in {r:?}"))
                        .clone()
                })
                .collect()
        })
        .collect()
}

/// Runs `touchdown report` and the example (with `--png` when given) on `file` in `dir`;
/// checks that their outcome counts (and the sweep's, `counts`) and allowable-slope tables
/// are the same. Returns the example's stdout.
fn compare_with_report(
    dir: &TempDir,
    file: &str,
    counts: &BTreeMap<String, String>,
    png: Option<&str>,
) -> String {
    let report = touchdown(dir.path(), &["report", file]);
    report.assert_ok();
    let mut args = vec![example_script().into_os_string(), file.into()];
    if let Some(png) = png {
        args.extend(["--png".into(), png.into()]);
    }
    let args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_os_str()).collect();
    let example = run_python(dir.path(), &args);
    let both = format!(
        "--- touchdown report {file} ---\n{}--- stability.py ---\n{example}",
        report.stdout
    );

    // Outcomes: the report's counts are the example's, and the sweep's.
    let outcomes = |text: &str| -> BTreeMap<String, String> {
        columns(&table(text, "## Outcomes"), &["outcome", "samples"])
            .into_iter()
            .map(|r| (r[0].clone(), r[1].clone()))
            .collect()
    };
    assert_eq!(
        outcomes(&example),
        outcomes(&report.stdout),
        "outcome counts of {file}:\n{both}"
    );
    assert_eq!(
        &outcomes(&example),
        counts,
        "outcome counts of {file} against the sweep's:\n{both}"
    );

    // Allowable slope per sector and its interval: the same table, cell for cell.
    let cols = [
        "azimuth sector",
        "samples",
        "stable",
        "allowable slope",
        "95 % interval",
    ];
    let example_sectors = columns(&table(&example, "## Allowable slope"), &cols);
    let report_sectors = columns(&table(&report.stdout, "## Allowable slope"), &cols);
    assert_eq!(example_sectors.len(), 8, "sectors of {file}:\n{both}");
    assert_eq!(
        example_sectors, report_sectors,
        "allowable slopes of {file}:\n{both}"
    );

    // The units come from the file's field metadata.
    let units = columns(&table(&example, "## Columns used"), &["column", "unit"]);
    for (column, unit) in [
        ("slope_deg", "deg"),
        ("downhill_azimuth_deg", "deg"),
        ("yaw_deg", "deg"),
    ] {
        assert!(
            units.contains(&vec![column.to_string(), unit.to_string()]),
            "no unit {unit} for {column}:\n{example}"
        );
    }
    example
}

/// Checks that `path` is a PNG of some substance (axes, thousands of points, a legend).
fn check_png(path: &Path) {
    let bytes = read_bytes(path);
    assert!(
        bytes.starts_with(PNG_MAGIC),
        "{} is not a PNG (starts {:?})",
        path.display(),
        &bytes[..bytes.len().min(8)]
    );
    assert!(
        bytes.len() > 20_000,
        "{} is only {} bytes: an empty plot?",
        path.display(),
        bytes.len()
    );
}

#[test]
fn stability_example_agrees_with_the_report() {
    if !python_readers_available("stability_example_agrees_with_the_report") {
        return;
    }
    let dir = TempDir::new("python-example");
    dir.write("steep.toml", STEEP);
    let mut tables = Vec::new();
    for format in ["arrow", "parquet"] {
        let out = format!("steep.{format}");
        let png = format!("steep-{format}.png");
        let counts = sweep(
            &dir,
            &[
                "--scenario",
                "steep.toml",
                "--samples",
                "4000",
                "--seed",
                "5",
                "--format",
                format,
                "--out",
                &out,
            ],
        );
        let example = compare_with_report(&dir, &out, &counts, Some(&png));
        check_png(&dir.join(&png));
        assert!(
            example.contains(&format!("wrote {png}")),
            "the example does not say it wrote {png}:\n{example}"
        );

        // Every sector has landers standing well past 30 deg, and the static limit of the
        // default gear (a side or a leg downhill in every sector) is printed with it.
        let sectors = table(&example, "## Allowable slope");
        for s in &sectors {
            let allowable: f64 = s["allowable slope"]
                .strip_suffix(" deg")
                .and_then(|a| a.parse().ok())
                .unwrap_or_else(|| panic!("no allowable slope in {s:?}:\n{example}"));
            assert!(
                (30.0..=56.0).contains(&allowable),
                "allowable slope {allowable} in {s:?}:\n{example}"
            );
            assert_eq!(s["static limit"], "44.7–54.4 deg", "{s:?}");
        }
        // Both formats hold the same sweep: the same tables.
        tables.push(
            example
                .lines()
                .filter(|l| l.starts_with('|'))
                .collect::<Vec<_>>()
                .join("\n"),
        );
    }
    assert_eq!(tables[0], tables[1], "the Arrow and Parquet files differ");

    // Without --png: the tables alone, no picture.
    let before = dir.entries();
    let args = [example_script().into_os_string(), "steep.arrow".into()];
    let args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_os_str()).collect();
    let tables_only = run_python(dir.path(), &args);
    assert!(!tables_only.contains("wrote"), "{tables_only}");
    assert_eq!(dir.entries(), before);

    // Slopes on a grid: many samples share a slope, and the allowable slope is taken only
    // at the last of equal slopes (a rule that reads the samples one by one differs here).
    let grid = STEEP.replace(
        r#"slope_deg = { dist = "uniform", min = 0.0, max = 60.0 }"#,
        r#"slope_deg = { dist = "grid", min = 0.0, max = 60.0, count = 121 }"#,
    );
    assert_ne!(grid, STEEP);
    dir.write("grid.toml", &grid);
    let counts = sweep(
        &dir,
        &[
            "--scenario",
            "grid.toml",
            "--samples",
            "3000",
            "--seed",
            "3",
            "--out",
            "grid.arrow",
        ],
    );
    compare_with_report(&dir, "grid.arrow", &counts, None);
}

#[test]
fn stability_example_static_limit_of_known_gear() {
    if !python_readers_available("stability_example_static_limit_of_known_gear") {
        return;
    }
    let dir = TempDir::new("python-example-limit");
    // The limit at a few azimuths for the default gear, the same gear given by its footpads
    // (one more inside the polygon, which must not count), and three legs.
    let code = r#"
import sys
sys.path.insert(0, sys.argv[1])
import stability as s
gears = {
    "default": "",
    "tips": "[lander]\nleg_tips_m = [[0.424264069, 0.424264069, -0.428936], [0.424264069, -0.424264069, -0.428936], [-0.424264069, -0.424264069, -0.428936], [-0.424264069, 0.424264069, -0.428936], [0.1, 0.0, -0.428936]]\n",
    "three": "[lander]\nlegs = 3\n",
}
for name, toml in gears.items():
    pads, h = s.footpads(toml)
    poly = s.support_polygon(pads)
    print(name, " ".join(f"{s.static_limit_deg(poly, h, phi):.2f}" for phi in (0, 45, 90, 180 + 45, 315)))
"#;
    let dir_arg = example_script()
        .parent()
        .expect("the example's folder")
        .to_path_buf();
    let out = run_python(
        dir.path(),
        &["-c".as_ref(), code.as_ref(), dir_arg.as_os_str()],
    );
    let limits: BTreeMap<&str, &str> = out.lines().filter_map(|l| l.split_once(' ')).collect();
    // Side downhill: atan(0.6 cos 45 / 0.428936) = 44.69 deg; leg downhill:
    // atan(0.6 / 0.428936) = 54.44 deg (docs/MODEL.md section 8).
    assert_eq!(
        limits.get("default"),
        Some(&"44.69 54.44 44.69 54.44 54.44"),
        "{out}"
    );
    assert_eq!(
        limits.get("tips"),
        Some(&"44.69 54.44 44.69 54.44 54.44"),
        "{out}"
    );
    // Three legs at 45, 165, 285 deg: a leg downhill at 45, a side (normal at 225) at
    // atan(0.6 cos 60 / 0.428936) = 34.97 deg.
    let three: Vec<&str> = limits
        .get("three")
        .unwrap_or_else(|| panic!("{out}"))
        .split(' ')
        .collect();
    assert_eq!((three[1], three[3]), ("54.44", "34.97"), "{out}");
}

/// Runs `touchdown trace ARGS --out OUT` in `dir` and writes what it printed to `OUT.txt`;
/// returns that file.
fn trace(dir: &TempDir, args: &[&str], out: &str) -> PathBuf {
    let mut all = vec!["trace", "--out", out];
    all.extend(args);
    let run = touchdown(dir.path(), &all);
    run.assert_ok();
    dir.write(&format!("{out}.txt"), &run.stdout)
}

#[test]
fn python_readers_hold_the_printed_values() {
    if !python_readers_available("python_readers_hold_the_printed_values") {
        return;
    }
    let dir = TempDir::new("python-values");
    dir.write("short.toml", SHORT);
    dir.write("three-legs.toml", THREE_LEGS);

    // Traces: metadata, first row, and (every step a row) the peaks of the printed summary.
    for (args, out) in [
        (&["--seed", "7", "--sample", "3"][..], "four-legs.arrow"),
        (
            &["--seed", "7", "--sample", "3", "--every", "10"][..],
            "every-10.arrow",
        ),
        (
            &["--scenario", "three-legs.toml", "--sample", "2"][..],
            "three-legs.arrow",
        ),
    ] {
        let printed = trace(&dir, args, out);
        run_python_check(
            "check_printed_values.py",
            &[
                "trace".as_ref(),
                dir.join(out).as_os_str(),
                printed.as_os_str(),
            ],
            &format!("the trace of `touchdown trace {}`", args.join(" ")),
        );
    }

    // Sweeps: the rows of a few samples hold the inputs `touchdown trace` prints for them.
    let samples = ["0", "1", "999"];
    let printouts: Vec<PathBuf> = samples
        .iter()
        .map(|i| {
            let args = [
                "--scenario",
                "short.toml",
                "--seed",
                "11",
                "--sample",
                i,
                "--every",
                "1e9",
            ];
            trace(&dir, &args, &format!("trace-{i}.arrow"))
        })
        .collect();
    for format in ["arrow", "parquet"] {
        let out = format!("short.{format}");
        let args = [
            "--scenario",
            "short.toml",
            "--samples",
            "1000",
            "--seed",
            "11",
            "--format",
            format,
            "--out",
            &out,
        ];
        sweep(&dir, &args);
        let path = dir.join(&out);
        let mut check: Vec<&std::ffi::OsStr> =
            vec!["sweep".as_ref(), path.as_os_str(), format.as_ref()];
        for (i, p) in samples.iter().zip(&printouts) {
            check.extend([i.as_ref(), p.as_os_str()]);
        }
        run_python_check(
            "check_printed_values.py",
            &check,
            &format!("the sweep file of `touchdown sweep {}`", args.join(" ")),
        );
    }
}

#[test]
fn stability_example_without_matplotlib_says_what_to_install() {
    if !python_readers_available("stability_example_without_matplotlib_says_what_to_install") {
        return;
    }
    let dir = TempDir::new("stability-no-matplotlib");
    sweep(&dir, &["--samples", "200", "--out", "s.arrow"]);
    // A matplotlib that cannot be imported, first on the path.
    std::fs::create_dir(dir.join("hide")).unwrap();
    std::fs::create_dir(dir.join("hide/matplotlib")).unwrap();
    dir.write(
        "hide/matplotlib/__init__.py",
        "raise ImportError(\"No module named 'matplotlib'\")\n",
    );
    let o = Command::new(python())
        .arg(example_script())
        .args(["s.arrow", "--png", "map.png"])
        .env("PYTHONPATH", dir.join("hide"))
        .current_dir(dir.path())
        .output()
        .expect("run the example");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("pip install matplotlib"), "{stderr}");
    assert!(!stderr.contains("Traceback"), "{stderr}");
    assert!(!dir.join("map.png").exists());
}
