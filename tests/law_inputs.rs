//! The built-in control laws' parameters are inputs like the others (issue 29, point 5):
//! Saltelli's design varies them and `sensitivity` lists them, `sweep --inputs` takes them
//! as columns, `study --vary` sets a drawn one (the value replaces its distribution) and a
//! thruster's key. `scenarios/hold-down.toml` draws its hold-down thrust from 0-40 N.

use crate::common::{TempDir, arrow_column, touchdown};
use arrow_array::Array as _;
use std::path::Path;
use touchdown::scenario::INPUT_FIELDS;

/// `scenarios/hold-down.toml`'s path.
fn hold_down() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios/hold-down.toml")
        .display()
        .to_string()
}

/// Column `name` of a sweep file, as `f64`.
fn column(path: &Path, name: &str) -> Vec<f64> {
    arrow_column(path, name).unwrap_or_else(|| panic!("{}: no column {name}", path.display()))
}

/// The `sample_seed` column of a sweep file, whole.
fn seeds(path: &Path) -> Vec<u64> {
    let file = std::fs::File::open(path).unwrap();
    let mut out = Vec::new();
    for b in arrow_ipc::reader::FileReader::try_new(file, None).unwrap() {
        let b = b.unwrap();
        let c = b.column_by_name("sample_seed").expect("sample_seed");
        let c = c
            .as_any()
            .downcast_ref::<arrow_array::UInt64Array>()
            .unwrap();
        out.extend((0..c.len()).map(|i| c.value(i)));
    }
    out
}

/// Panics unless `run` succeeded (a sweep says on stderr what it runs, even `--quiet`).
fn succeeded(run: &crate::common::Run) {
    assert_eq!(run.code, Some(0), "{run}");
}

/// The scenario text a sweep file stores in its metadata.
fn stored_scenario(path: &Path) -> touchdown::scenario::Scenario {
    let file = std::fs::File::open(path).unwrap();
    let r = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
    let text = r.schema().metadata()["touchdown.scenario"].clone();
    touchdown::scenario::Scenario::from_toml(&text).unwrap()
}

#[test]
fn law_inputs_saltelli_varies_the_hold_down_thrust_and_sensitivity_lists_it() {
    let dir = TempDir::new("law-inputs-saltelli");
    // hold-down.toml draws 11 inputs and the hold-down thrust: blocks of 14; 256 base
    // points.
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--scenario",
            &hold_down(),
            "--design",
            "sobol-indices",
            "--samples",
            "3584",
            "--out",
            "s.arrow",
        ],
    );
    succeeded(&run);
    let path = dir.join("s.arrow");
    let (thrust, slope) = (
        column(&path, "hold_down_thrust_n"),
        column(&path, "slope_deg"),
    );
    // The thrust is the last varied value (after the 11 inputs): AB_11 takes B's thrust and
    // keeps A's slope; every other row of the block keeps A's thrust.
    for base in 0..256 {
        let row = |m: usize| 14 * base + m;
        assert_ne!(thrust[row(0)], thrust[row(1)], "base {base}: A and B");
        for q in 0..11 {
            assert_eq!(thrust[row(2 + q)], thrust[row(0)], "base {base}, AB_{q}");
        }
        assert_eq!(thrust[row(13)], thrust[row(1)], "base {base}, AB_11");
        assert_eq!(slope[row(13)], slope[row(0)], "base {base}, AB_11");
    }
    let run = touchdown(
        dir.path(),
        &["sensitivity", "s.arrow", "--bootstrap", "200"],
    );
    run.assert_ok();
    let report = &run.stdout;
    assert!(report.contains("256 base points"), "{report}");
    // The rows of the P(tipped) table: input, S_i, ST_i.
    let rows: Vec<(String, f64, f64)> = report
        .split("## P(tipped)")
        .nth(1)
        .expect("a P(tipped) section")
        .split("\n## ")
        .next()
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| input"))
        .map(|l| {
            let f: Vec<&str> = l.split('|').map(str::trim).collect();
            (
                f[1].to_string(),
                f[2].parse().unwrap(),
                f[4].parse().unwrap(),
            )
        })
        .collect();
    println!("{report}");
    assert_eq!(rows.len(), 12, "11 inputs and the thrust: {rows:?}");
    let (name, first, total) = rows
        .iter()
        .find(|r| r.0 == "hold_down_thrust_n")
        .expect("hold_down_thrust_n is listed")
        .clone();
    // Whether a lander tips is above all its hold-down thrust's doing (the issue: 58 %
    // tipped below 10 N, none above 30 N): its first-order index measured 0.47 (95 %
    // interval 0.28 to 0.64) at these 256 base points, every other input's at most 0.04.
    // Asked here: at least 0.3, and larger than any other input's by at least 0.2.
    assert!(first > 0.3 && total > 0.3, "{name}: S {first}, ST {total}");
    for (other, s, _) in rows.iter().filter(|r| r.0 != name) {
        assert!(
            s + 0.2 < first,
            "{other}: S {s} against the thrust's {first}"
        );
    }
}

/// A CSV table of rows `rows` of the sweep at `path`: the sample seed, the 12 inputs and
/// `thrust(i)` as the hold-down thrust of row `i` (Rust's shortest round-trip decimals).
fn table(path: &Path, rows: usize, thrust: impl Fn(usize) -> f64) -> String {
    let seed = seeds(path);
    let inputs: Vec<Vec<f64>> = INPUT_FIELDS.iter().map(|(n, _)| column(path, n)).collect();
    let mut text = String::from("sample_seed");
    for (n, _) in INPUT_FIELDS {
        text += &format!(",{n}");
    }
    text += ",hold_down_thrust_n\n";
    for i in 0..rows {
        text += &seed[i].to_string();
        for c in &inputs {
            text += &format!(",{}", c[i]);
        }
        text += &format!(",{}\n", thrust(i));
    }
    text
}

#[test]
fn law_inputs_a_table_column_replaces_the_drawn_hold_down_thrust() {
    let dir = TempDir::new("law-inputs-table");
    let sweep = |out: &str, extra: &[&str]| {
        let mut args = vec![
            "sweep",
            "--quiet",
            "--scenario",
            "hd.toml",
            "--samples",
            "8",
            "--out",
            out,
        ];
        args.extend_from_slice(extra);
        touchdown(dir.path(), &args)
    };
    std::fs::copy(hold_down(), dir.join("hd.toml")).unwrap();
    succeeded(&sweep("s.arrow", &[]));
    let s = dir.join("s.arrow");
    let drawn = column(&s, "hold_down_thrust_n");
    // The sweep's own thrusts, replayed with its seeds and inputs: the same landers, bit
    // for bit.
    dir.write("same.csv", &table(&s, 8, |i| drawn[i]));
    succeeded(&sweep("same.arrow", &["--inputs", "same.csv"]));
    for name in [
        "hold_down_thrust_n",
        "hold_down_impulse_n_s",
        "propellant_kg",
        "decided_s",
        "final_tilt_deg",
    ] {
        let (a, b) = (column(&s, name), column(&dir.join("same.arrow"), name));
        assert!(
            a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
            "{name}: {a:?} against {b:?}"
        );
    }
    // Thrusts of the table's own: 0 N (the hold-down fires nothing) and 30 N in turn.
    let thrust = |i: usize| if i.is_multiple_of(2) { 0.0 } else { 30.0 };
    dir.write("mine.csv", &table(&s, 8, thrust));
    succeeded(&sweep("mine.arrow", &["--inputs", "mine.csv"]));
    let mine = dir.join("mine.arrow");
    let (given, impulse, contact) = (
        column(&mine, "hold_down_thrust_n"),
        column(&mine, "hold_down_impulse_n_s"),
        column(&mine, "first_contact_s"),
    );
    for i in 0..8 {
        assert_eq!(given[i], thrust(i), "row {i}");
        if thrust(i) == 0.0 {
            assert_eq!(impulse[i], 0.0, "row {i}: a hold-down of 0 N");
        } else if contact[i].is_finite() {
            assert!(impulse[i] > 0.0, "row {i}: a hold-down of 30 N");
        }
    }
    // Refused, naming the column and the key: a thrust the thrusters cannot give, one
    // below 0, and the column in a scenario without a hold-down.
    dir.write("strong.csv", &table(&s, 2, |_| 100.0));
    let run = sweep("strong.arrow", &["--inputs", "strong.csv"]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains("control.hold_down.thrust_n") && run.stderr.contains("strong.csv"),
        "{}",
        run.stderr
    );
    dir.write("negative.csv", &table(&s, 2, |_| -1.0));
    let run = sweep("negative.arrow", &["--inputs", "negative.csv"]);
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains("row 0") && run.stderr.contains("column hold_down_thrust_n"),
        "{}",
        run.stderr
    );
    dir.write("plain.csv", "slope_deg,hold_down_thrust_n\n10.0,20.0\n");
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--quiet",
            "--inputs",
            "plain.csv",
            "--out",
            "p.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert!(
        run.stderr.contains("hold_down_thrust_n") && run.stderr.contains("[control.hold_down]"),
        "{}",
        run.stderr
    );
}

#[test]
fn law_inputs_study_varies_a_drawn_law_parameter_and_a_thrusters_key() {
    let dir = TempDir::new("law-inputs-study");
    let study = |vary: &str, out: &str| {
        touchdown(
            dir.path(),
            &[
                "study",
                "--quiet",
                "--scenario",
                &hold_down(),
                "--vary",
                vary,
                "--samples",
                "8",
                "--out-dir",
                out,
            ],
        )
    };
    // The drawn thrust (uniform 0-40 N): each value replaces the distribution.
    study("control.hold_down.thrust_n=0:40:3", "thrust").assert_ok();
    for (file, value) in [
        ("00-thrust_n-0.arrow", 0.0),
        ("01-thrust_n-20.arrow", 20.0),
        ("02-thrust_n-40.arrow", 40.0),
    ] {
        let thrust = column(&dir.join("thrust").join(file), "hold_down_thrust_n");
        assert_eq!(thrust, vec![value; 8], "{file}");
    }
    // A thruster's key, by its index in [[thrusters]]: an attitude thruster's thrust.
    study("thrusters.4.max_thrust_n=0.5:1.5:2", "thruster").assert_ok();
    for (file, value) in [
        ("00-max_thrust_n-0.5.arrow", 0.5),
        ("01-max_thrust_n-1.5.arrow", 1.5),
    ] {
        let s = stored_scenario(&dir.join("thruster").join(file));
        assert_eq!(s.thrusters[4].max_thrust_n, value, "{file}");
        assert_eq!(
            s.thrusters[5].max_thrust_n, 1.0,
            "{file}: the others as they were"
        );
    }
    // Refused before any work, naming the key: an index past the list, an unknown key
    // of a thruster, a thrust below 0, the list without an index.
    for (vary, says) in [
        ("thrusters.12.max_thrust_n=1:2:2", "indices 0 to 11"),
        ("thrusters.2.thrust=1:2:2", "thrusters[2].thrust"),
        (
            "thrusters.4.max_thrust_n=-1:1:2",
            "thrusters[4].max_thrust_n",
        ),
        ("thrusters.max_thrust_n=1:2:2", "thrusters.0.KEY"),
    ] {
        let run = study(vary, "refused");
        assert_eq!(run.code, Some(2), "{vary}: {}", run.stderr);
        assert!(run.stderr.contains(says), "{vary}: {}", run.stderr);
        assert!(!dir.join("refused").join("study.arrow").exists(), "{vary}");
    }
}
