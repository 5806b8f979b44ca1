//! End-to-end tests of the command line: the `touchdown` binary run as a user runs it.
//!
//! Every test works in a fresh folder of its own under the system temp folder, removed when
//! the test passes and kept (its path printed) when it fails.

use crate::common::{
    BadInput, TempDir, bad_args, bad_scenario, check_bad_input, python_readers_available,
    read_bytes, run_python_check, touchdown,
};
use arrow_array::{Array, Float64Array};
use arrow_ipc::reader::FileReader;
use std::collections::HashMap;
use std::path::Path;

/// The numbers of the `wrote PATH: R rows (every E of S steps, and the state at the
/// decision)` line.
#[derive(Debug, PartialEq)]
struct Wrote {
    path: String,
    rows: u64,
    every: u64,
    steps: u64,
}

fn wrote(stdout: &str) -> Wrote {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("wrote "))
        .unwrap_or_else(|| panic!("no `wrote` line in\n{stdout}"));
    let parse = || -> Option<Wrote> {
        let (path, rest) = line.strip_prefix("wrote ")?.rsplit_once(": ")?;
        let w: Vec<&str> = rest.split_whitespace().collect();
        // ["R", "rows", "(every", "E", "of", "S", "steps,", "and the state at the decision)"]
        if w.len() != 13
            || w[1] != "rows"
            || w[2] != "(every"
            || w[6] != "steps,"
            || w[7..].join(" ") != "and the state at the decision)"
        {
            return None;
        }
        Some(Wrote {
            path: path.to_string(),
            rows: w[0].parse().ok()?,
            every: w[3].parse().ok()?,
            steps: w[5].parse().ok()?,
        })
    };
    parse().unwrap_or_else(|| panic!("cannot read the line {line:?}"))
}

/// The step count of the summary's `outcome ... (N steps)` line.
fn summary_steps(stdout: &str) -> u64 {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("outcome "))
        .unwrap_or_else(|| panic!("no outcome line in\n{stdout}"));
    line.rsplit_once('(')
        .and_then(|(_, r)| r.strip_suffix(" steps)"))
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("cannot read the steps of {line:?}"))
}

/// The outcome word of the summary's `outcome` line.
fn summary_outcome(stdout: &str) -> String {
    stdout
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("outcome "))
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_else(|| panic!("no outcome line in\n{stdout}"))
        .to_string()
}

/// The standard output without its `wrote` line, which names the output path.
fn without_wrote_line(stdout: &str) -> String {
    stdout
        .lines()
        .filter(|l| !l.starts_with("wrote "))
        .collect::<Vec<_>>()
        .join("\n")
}

/// An Arrow IPC file as the Rust reader sees it.
struct Trace {
    rows: usize,
    columns: Vec<String>,
    metadata: HashMap<String, String>,
    t_s: Vec<f64>,
}

fn read_trace(path: &Path) -> Trace {
    let file =
        std::fs::File::open(path).unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()));
    let reader = FileReader::try_new(file, None)
        .unwrap_or_else(|e| panic!("{} is not an Arrow IPC file: {e}", path.display()));
    let schema = reader.schema();
    let columns = schema.fields().iter().map(|f| f.name().clone()).collect();
    let metadata: HashMap<String, String> = schema.metadata().clone().into();
    let mut rows = 0;
    let mut t_s = Vec::new();
    for batch in reader {
        let batch = batch.expect("a readable record batch");
        rows += batch.num_rows();
        let t = batch
            .column_by_name("t_s")
            .expect("a t_s column")
            .as_any()
            .downcast_ref::<Float64Array>()
            .expect("t_s is Float64");
        assert_eq!(t.null_count(), 0);
        t_s.extend(t.values().iter());
    }
    Trace {
        rows,
        columns,
        metadata,
        t_s,
    }
}

// ---------------------------------------------------------------------------------------
// 1. Bad input.

const BAD_INPUTS: &[BadInput] = &[
    // Unknown keys, with the hint of the closest known key.
    bad_scenario(
        "unknown top-level key",
        "colour = \"red\"\n",
        &["scenario key `colour` is unknown", "this table knows:"],
    ),
    bad_scenario(
        "misspelt top-level key",
        "sed = 3\n",
        &["`sed` is unknown", "did you mean `seed`?"],
    ),
    bad_scenario(
        "misspelt nested key",
        "[lander]\nmas_kg = 5\n",
        &["`lander.mas_kg` is unknown", "did you mean `mass_kg`?"],
    ),
    bad_scenario(
        "misspelt key two tables down",
        "[surface.roughness]\nrms_heigth_m = 0.01\n",
        &[
            "`surface.roughness.rms_heigth_m` is unknown",
            "did you mean `rms_height_m`?",
        ],
    ),
    bad_scenario(
        "unknown key in a distribution",
        "[inputs]\nslope_deg = { dist = \"uniform\", min = 0, max = 10, mode = 3 }\n",
        &["`inputs.slope_deg.mode` is unknown"],
    ),
    // Wrong types.
    bad_scenario(
        "string for a number",
        "[lander]\nmass_kg = \"heavy\"\n",
        &["`lander.mass_kg` = \"heavy\"", "expected a number"],
    ),
    bad_scenario(
        "number for a table",
        "lander = 5\n",
        &["`lander` = 5", "expected a table"],
    ),
    bad_scenario(
        "float for an integer",
        "seed = 1.5\n",
        &["`seed` = 1.5", "whole number"],
    ),
    // Out of range.
    bad_scenario(
        "negative mass",
        "[lander]\nmass_kg = -5\n",
        &["`lander.mass_kg` = -5 ", "greater than 0"],
    ),
    bad_scenario(
        "zero mass",
        "[lander]\nmass_kg = 0\n",
        &["`lander.mass_kg` = 0 ", "greater than 0"],
    ),
    bad_scenario(
        "inertia against the triangle inequality",
        "[lander]\ninertia_kg_m2 = [1, 1, 5]\n",
        &["`lander.inertia_kg_m2` = [1, 1, 5]", "triangle inequality"],
    ),
    bad_scenario(
        "slope of 90 deg",
        "[inputs]\nslope_deg = 90\n",
        &["`inputs.slope_deg` = 90 ", "not including, 90 deg"],
    ),
    bad_scenario(
        "slope of 95 deg",
        "[inputs]\nslope_deg = 95\n",
        &["`inputs.slope_deg` = 95 ", "not including, 90 deg"],
    ),
    bad_scenario(
        "uniform slope up to 90 deg",
        "[inputs]\nslope_deg = { dist = \"uniform\", min = 0, max = 90 }\n",
        &["`inputs.slope_deg`", "max = 90", "not including, 90 deg"],
    ),
    bad_scenario(
        "log-uniform from 0",
        "[surface]\nstiffness_n_per_m = { dist = \"log-uniform\", min = 0, max = 1e5 }\n",
        &["`surface.stiffness_n_per_m`", "min = 0", "min above 0"],
    ),
    bad_scenario(
        "log-uniform with min above max",
        "[surface]\nstiffness_n_per_m = { dist = \"log-uniform\", min = 1e5, max = 1e4 }\n",
        &["`surface.stiffness_n_per_m`", "min at most max"],
    ),
    bad_scenario(
        "uniform with min above max",
        "[inputs]\nroll_deg = { dist = \"uniform\", min = 5, max = 1 }\n",
        &["`inputs.roll_deg`", "min = 5", "min at most max"],
    ),
    bad_scenario(
        "zero step",
        "[simulation]\nstep_s = 0\n",
        &["`simulation.step_s` = 0 ", "greater than 0"],
    ),
    bad_scenario(
        "negative step",
        "[simulation]\nstep_s = -0.001\n",
        &["`simulation.step_s` = -0.001 ", "greater than 0"],
    ),
    bad_scenario(
        "too few legs",
        "[lander]\nlegs = 2\n",
        &["`lander.legs` = 2 ", "from 3 to 64"],
    ),
    // Not finite.
    bad_scenario(
        "nan mass",
        "[lander]\nmass_kg = nan\n",
        &["`lander.mass_kg` = nan ", "finite"],
    ),
    bad_scenario(
        "nan in a distribution",
        "[inputs]\nroll_deg = { dist = \"normal\", mean = nan, sd = 1, min = -5, max = 5 }\n",
        &["`inputs.roll_deg.mean` = nan ", "finite"],
    ),
    bad_scenario(
        "inf mass",
        "[lander]\nmass_kg = inf\n",
        &["`lander.mass_kg` = inf ", "finite"],
    ),
    bad_scenario(
        "inf in a distribution",
        "[inputs]\nrelease_height_m = { dist = \"uniform\", min = 5, max = inf }\n",
        &["`inputs.release_height_m.max` = inf ", "finite"],
    ),
    // Not TOML.
    bad_scenario(
        "unclosed table header",
        "seed = 3\n[lander\nmass_kg = 5\n",
        &["not valid TOML", "line 2", "[lander"],
    ),
    bad_scenario(
        "doubled equals sign",
        "[lander]\nmass_kg = = 5\n",
        &["not valid TOML", "line 2", "mass_kg = = 5"],
    ),
    bad_scenario(
        "duplicate key",
        "seed = 1\nseed = 2\n",
        &["not valid TOML", "line 2", "seed"],
    ),
    // Distributions.
    bad_scenario(
        "unknown distribution kind",
        "[inputs]\nslope_deg = { dist = \"weibull\", min = 0, max = 10 }\n",
        &["`inputs.slope_deg.dist` = \"weibull\"", "\"uniform\""],
    ),
    bad_scenario(
        "distribution without its kind",
        "[inputs]\nslope_deg = { min = 0, max = 10 }\n",
        &[
            "`inputs.slope_deg` = { max = 10, min = 0 }",
            "dist = \"uniform\"",
        ],
    ),
    bad_scenario(
        "distribution missing a bound",
        "[inputs]\nslope_deg = { dist = \"uniform\", min = 0 }\n",
        &["`inputs.slope_deg`", "`max` in a \"uniform\" distribution"],
    ),
    bad_scenario(
        "untruncated normal on slope_deg",
        "[inputs]\nslope_deg = { dist = \"normal\", mean = 10, sd = 2 }\n",
        &[
            "`inputs.slope_deg`",
            "dist = \"normal\"",
            "untruncated normal",
            "give min and max",
        ],
    ),
    bad_scenario(
        "normal on slope_deg truncated on one side only",
        "[inputs]\nslope_deg = { dist = \"normal\", mean = 10, sd = 2, min = 0 }\n",
        &["`inputs.slope_deg`", "min = 0", "give min and max"],
    ),
    // Files and flags.
    bad_args(
        "missing scenario file",
        &["--scenario", "missing.toml"],
        &["cannot read scenario file missing.toml"],
    ),
    bad_args(
        "sample not a number",
        &["--sample", "abc"],
        &["--sample", "'abc'", "not a whole number"],
    ),
    bad_args("negative sample", &["--sample", "-1"], &["--sample", "-1"]),
    bad_args("negative seed", &["--seed", "-1"], &["--seed", "-1"]),
    bad_args(
        "negative sample, with =",
        &["--sample=-1"],
        &["--sample", "'-1'", "not a whole number"],
    ),
    bad_args(
        "fractional sample",
        &["--sample", "1.5"],
        &["--sample", "'1.5'", "not a whole number"],
    ),
    bad_args(
        "seed not a number",
        &["--seed", "x7"],
        &["--seed", "'x7'", "not a whole number"],
    ),
    bad_args(
        "zero every",
        &["--every", "0"],
        &["--every", "'0'", "at least 1"],
    ),
    bad_args(
        "output in a missing folder",
        &["--out", "missing/out.arrow"],
        &["missing/out.arrow", "folder missing does not exist"],
    ),
    bad_args(
        "output path that names no file",
        &["--out", "."],
        &["output path \".\"", "names no file"],
    ),
    // Limits that every sample breaks: a stroke margin of the whole stroke or more.
    bad_scenario(
        "stroke margin beyond the stroke",
        "[damper]\nenabled = true\n[limits]\nstroke_margin_m = 1.0\n",
        &[
            "`limits.stroke_margin_m` = 1 m",
            "less than the damper's usable stroke, 0.05 m (damper.usable_stroke_m)",
            "every sample that strokes at all would break it",
        ],
    ),
    bad_scenario(
        "stroke margin of two stages' whole stroke",
        "[damper]\nenabled = true\nstages = [{ stroke_m = 0.02, crush_strength_psi = 50.0 }, \
         { stroke_m = 0.03, crush_strength_psi = 90.0 }]\n[limits]\nstroke_margin_m = 0.05\n",
        &["the 2 damper.stages' stroke_m summed"],
    ),
    // A bad scenario is refused before the output file is made, wherever it goes.
    BadInput {
        name: "bad scenario with an explicit output path",
        scenario: Some("[lander]\nmass_kg = 0\n"),
        args: &["--out", "explicit.arrow"],
        expect: &["`lander.mass_kg` = 0 "],
    },
];

#[test]
fn bad_input_is_refused_with_a_message_naming_key_and_value() {
    let failures: Vec<String> = BAD_INPUTS
        .iter()
        .flat_map(|case| check_bad_input("trace", case, &[]))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs were not refused properly:\n\n{}",
        failures.len(),
        BAD_INPUTS.len(),
        failures.join("\n\n")
    );
}

// ---------------------------------------------------------------------------------------
// 2. The printed default scenario.

#[test]
fn printed_scenario_reads_back_as_the_default() {
    let dir = TempDir::new("scenario-round-trip");
    let printed = touchdown(dir.path(), &["scenario"]);
    printed.assert_ok();
    assert_eq!(printed.stdout, touchdown::scenario::DEFAULT_TOML);
    dir.write("default.toml", &printed.stdout);

    let from_file = touchdown(
        dir.path(),
        &["trace", "--scenario", "default.toml", "--out", "a.arrow"],
    );
    from_file.assert_ok();
    let built_in = touchdown(dir.path(), &["trace", "--out", "b.arrow"]);
    built_in.assert_ok();

    assert_eq!(wrote(&from_file.stdout).path, "a.arrow");
    assert_eq!(wrote(&built_in.stdout).path, "b.arrow");
    assert_eq!(
        without_wrote_line(&from_file.stdout),
        without_wrote_line(&built_in.stdout),
        "the printed scenario does not run like the built-in default"
    );
    // The same scenario text is stored as provenance, so the files are the same too.
    assert!(
        read_bytes(&dir.join("a.arrow")) == read_bytes(&dir.join("b.arrow")),
        "trace files of the printed and the built-in default differ"
    );
}

// ---------------------------------------------------------------------------------------
// 3. A trace file.

#[test]
fn trace_rows_match_the_summary_and_runs_repeat_exactly() {
    let dir = TempDir::new("trace");
    let args = |out: &'static str, sample: &'static str| {
        [
            "trace", "--sample", sample, "--seed", "7", "--every", "10", "--out", out,
        ]
    };
    let first = touchdown(dir.path(), &args("a.arrow", "3"));
    first.assert_ok();
    assert!(
        first.stdout.starts_with("sample 3 of seed 7 "),
        "{}",
        first.stdout
    );

    let steps = summary_steps(&first.stdout);
    let w = wrote(&first.stdout);
    assert_eq!(
        w,
        Wrote {
            path: "a.arrow".into(),
            rows: steps.div_ceil(10) + 1,
            every: 10,
            steps,
        },
        "{}",
        first.stdout
    );
    assert!(
        steps > 10,
        "too short a sample to test --every: {steps} steps"
    );

    let trace = read_trace(&dir.join("a.arrow"));
    assert_eq!(trace.rows as u64, w.rows);
    assert!(
        trace.t_s.windows(2).all(|p| p[0] < p[1]),
        "t_s does not increase"
    );
    let meta = |k: &str| trace.metadata.get(k).map(String::as_str);
    assert_eq!(meta("touchdown.seed"), Some("7"));
    assert_eq!(meta("touchdown.sample"), Some("3"));
    assert_eq!(meta("touchdown.every"), Some("10"));
    assert_eq!(meta("touchdown.kind"), Some("trace"));
    assert_eq!(
        meta("touchdown.outcome"),
        Some(summary_outcome(&first.stdout).as_str())
    );
    // The scenario that ran, with the seed of --seed.
    assert_eq!(
        meta("touchdown.scenario"),
        Some(touchdown::scenario::DEFAULT_TOML.replace("\nseed = 1\n", "\nseed = 7\n")).as_deref()
    );
    for leg in 0..4 {
        assert!(
            trace.columns.contains(&format!("leg{leg}_normal_force_n")),
            "no columns of leg {leg} in {:?}",
            trace.columns
        );
    }

    // Twice the same command: the same file, byte for byte.
    let second = touchdown(dir.path(), &args("b.arrow", "3"));
    second.assert_ok();
    assert_eq!(
        without_wrote_line(&first.stdout),
        without_wrote_line(&second.stdout)
    );
    assert!(
        read_bytes(&dir.join("a.arrow")) == read_bytes(&dir.join("b.arrow")),
        "two runs of the same command wrote different files"
    );

    // Overwriting an existing file leaves no partial file behind.
    touchdown(dir.path(), &args("a.arrow", "3")).assert_ok();
    assert_eq!(dir.entries(), ["a.arrow", "b.arrow"]);

    // A sample index in scientific notation is the same sample.
    let ten = touchdown(dir.path(), &args("ten.arrow", "10"));
    ten.assert_ok();
    let sci = touchdown(dir.path(), &args("sci.arrow", "1e1"));
    sci.assert_ok();
    assert!(
        ten.stdout.starts_with("sample 10 of seed 7 "),
        "{}",
        ten.stdout
    );
    assert_eq!(
        without_wrote_line(&ten.stdout),
        without_wrote_line(&sci.stdout)
    );
    assert!(
        read_bytes(&dir.join("ten.arrow")) == read_bytes(&dir.join("sci.arrow")),
        "--sample 1e1 and --sample 10 wrote different files"
    );
    assert!(
        read_bytes(&dir.join("ten.arrow")) != read_bytes(&dir.join("a.arrow")),
        "samples 10 and 3 wrote the same file"
    );
}

#[test]
fn every_step_is_a_row_by_default() {
    let dir = TempDir::new("trace-every-1");
    let run = touchdown(dir.path(), &["trace"]);
    run.assert_ok();
    let w = wrote(&run.stdout);
    assert_eq!(w.path, "trace.arrow");
    assert_eq!((w.every, w.steps), (1, summary_steps(&run.stdout)));
    assert_eq!(
        w.rows,
        w.steps + 1,
        "a row per step and one of the decision"
    );
    assert_eq!(read_trace(&dir.join("trace.arrow")).rows as u64, w.rows);
}

// ---------------------------------------------------------------------------------------
// 4. Python readers.

/// Runs `check_trace.py` on a file the binary writes with `args`.
fn check_with_python(dir: &TempDir, args: &[&str], out: &str, legs: usize) {
    let mut all = vec!["trace", "--out", out];
    all.extend(args);
    let run = touchdown(dir.path(), &all);
    run.assert_ok();
    let w = wrote(&run.stdout);
    assert_eq!(w.rows, w.steps.div_ceil(w.every) + 1);

    run_python_check(
        "check_trace.py",
        &[
            dir.join(out).as_os_str(),
            w.rows.to_string().as_ref(),
            legs.to_string().as_ref(),
        ],
        &format!("the trace of `touchdown {}`", all.join(" ")),
    );
}

#[test]
fn python_readers_open_the_trace() {
    if !python_readers_available("python_readers_open_the_trace") {
        return;
    }
    let dir = TempDir::new("python");
    check_with_python(&dir, &[], "four-legs.arrow", 4);
    dir.write("three-legs.toml", "[lander]\nlegs = 3\n");
    check_with_python(
        &dir,
        &[
            "--scenario",
            "three-legs.toml",
            "--sample",
            "2",
            "--every",
            "7",
        ],
        "three-legs.arrow",
        3,
    );
}
