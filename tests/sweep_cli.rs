//! End-to-end tests of `touchdown sweep`: the binary run as a user runs it, its file read
//! back in Rust and in Python, against its closing summary and against `touchdown trace`.
//!
//! Every sweep is small (a few thousand samples of a scenario cut at 20 s) so that the
//! whole file runs in seconds. Every test works in a fresh folder of its own under the
//! system temp folder, removed when the test passes and kept when it fails.

use crate::common::{
    BadInput, Run, SHORT, THREE_LEGS, TempDir, bad_args, bad_scenario, check_bad_input,
    python_readers_available, read_bytes, run_python_check, touchdown,
};
use arrow_array::{Array, Float64Array, RecordBatch, StringArray, UInt32Array, UInt64Array};
use arrow_ipc::reader::FileReader;
use arrow_schema::SchemaRef;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};
use touchdown::reference::Outcome;
use touchdown::scenario::INPUT_FIELDS;

/// The short scenario on rough terrain (terrain tiles and landing-point offsets).
const ROUGH: &str = "[simulation]\nt_max_s = 20.0\n\n[surface.roughness]\nrms_height_m = 0.02\n";

// ---------------------------------------------------------------------------------------
// What the binary prints.

/// The one-line banner on stderr:
/// `touchdown sweep: N samples, seed S, kernel K ISA (L landers per block), T threads`.
#[derive(Debug, PartialEq)]
struct Banner {
    samples: u64,
    seed: u64,
    threads: usize,
}

fn banner(run: &Run) -> Banner {
    let mut lines = run.stderr.lines();
    let (Some(line), None) = (lines.next(), lines.next()) else {
        panic!("expected the banner alone on stderr of {run}");
    };
    let parse = || -> Option<Banner> {
        let rest = line.strip_prefix("touchdown sweep: ")?;
        let parts: Vec<&str> = rest.split(", ").collect();
        // ["N samples", "seed S", "kernel K ISA (L landers per block)", "T threads"], and
        // "shard K/N (samples A..B of M)" after them for a shard.
        let shard_note = parts.len() == 5 && parts[4].starts_with("shard ");
        if !(parts.len() == 4 || shard_note) || !parts[2].starts_with("kernel ") {
            return None;
        }
        Some(Banner {
            samples: parts[0].strip_suffix(" samples")?.parse().ok()?,
            seed: parts[1].strip_prefix("seed ")?.parse().ok()?,
            threads: parts[3]
                .strip_suffix(" threads")
                .or_else(|| parts[3].strip_suffix(" thread"))?
                .parse()
                .ok()?,
        })
    };
    parse().unwrap_or_else(|| panic!("cannot read the banner {line:?} of {run}"))
}

/// The closing summary on stdout.
#[derive(Debug)]
struct Summary {
    /// The `samples` line.
    samples: u64,
    /// The `outcomes` block: every outcome with its count, zeros included.
    outcomes: BTreeMap<String, u64>,
    /// The path of the `wrote` line.
    wrote: String,
}

fn summary(run: &Run) -> Summary {
    let stdout = &run.stdout;
    let value = |key: &str| -> &str {
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(key).filter(|r| r.starts_with(' ')))
            .map(str::trim)
            .unwrap_or_else(|| panic!("no `{key}` line in the summary of {run}"))
    };
    let samples: u64 = value("samples")
        .parse()
        .unwrap_or_else(|_| panic!("cannot read the `samples` line of {run}"));
    for key in [
        "wall time",
        "samples/s",
        "lander-steps/s",
        "mean steps per sample",
        "lane occupancy",
    ] {
        value(key);
    }
    let wrote = value("wrote").to_string();

    let mut outcomes = BTreeMap::new();
    let block = stdout
        .lines()
        .skip_while(|l| *l != "outcomes")
        .skip(1)
        .take_while(|l| l.starts_with("  "));
    for line in block {
        // "  tipped           2789   92.97 %"
        let w: Vec<&str> = line.split_whitespace().collect();
        let count: Option<u64> = w.get(1).and_then(|c| c.parse().ok());
        let (4, Some(count), Some(&"%")) = (w.len(), count, w.get(3)) else {
            panic!("cannot read the outcome line {line:?} of {run}");
        };
        let percent = format!("{:.2}", 100.0 * count as f64 / samples as f64);
        assert_eq!(
            w[2], percent,
            "the percentage of the line {line:?} is not {count} of {samples}, in {run}"
        );
        assert!(
            outcomes.insert(w[0].to_string(), count).is_none(),
            "outcome {} listed twice in {run}",
            w[0]
        );
    }
    let names: BTreeSet<&str> = outcomes.keys().map(String::as_str).collect();
    let all: BTreeSet<&str> = Outcome::ALL.iter().map(|o| o.name()).collect();
    assert_eq!(names, all, "the outcomes block of {run}");
    assert_eq!(
        outcomes.values().sum::<u64>(),
        samples,
        "the outcome counts do not add up to the samples in {run}"
    );
    Summary {
        samples,
        outcomes,
        wrote,
    }
}

/// Runs `touchdown sweep ARGS` in `dir`; panics unless it succeeded with its banner alone on
/// stderr and a closing summary that agree with each other.
fn sweep(dir: &TempDir, args: &[&str]) -> (Banner, Summary) {
    let mut all = vec!["sweep"];
    all.extend(args);
    let run = touchdown(dir.path(), &all);
    assert!(run.code == Some(0), "expected success of {run}");
    let (b, s) = (banner(&run), summary(&run));
    assert_eq!(b.samples, s.samples, "banner and summary of {run}");
    (b, s)
}

// ---------------------------------------------------------------------------------------
// The sweep file as the Rust readers see it.

/// A sweep file read whole, Arrow IPC or Parquet.
pub(crate) struct SweepFile {
    schema: SchemaRef,
    batches: Vec<RecordBatch>,
}

pub(crate) fn read_sweep(path: &Path) -> SweepFile {
    let bytes = read_bytes(path);
    let open = || {
        std::fs::File::open(path).unwrap_or_else(|e| panic!("cannot open {}: {e}", path.display()))
    };
    let batches: Vec<RecordBatch>;
    let schema;
    if bytes.starts_with(b"ARROW1") {
        let reader = FileReader::try_new(open(), None)
            .unwrap_or_else(|e| panic!("{} is not an Arrow IPC file: {e}", path.display()));
        schema = reader.schema();
        batches = reader
            .map(|b| b.expect("a readable record batch"))
            .collect();
    } else if bytes.starts_with(b"PAR1") {
        let builder = ParquetRecordBatchReaderBuilder::try_new(open())
            .unwrap_or_else(|e| panic!("{} is not a Parquet file: {e}", path.display()));
        schema = builder.schema().clone();
        // Batches as large as the writer's, so that both formats cut the rows alike.
        let reader = builder
            .with_batch_size(touchdown::output::format::BATCH_ROWS)
            .build()
            .expect("a Parquet reader");
        batches = reader
            .map(|b| b.expect("a readable record batch"))
            .collect();
    } else {
        panic!("{} is neither Arrow IPC nor Parquet", path.display());
    }
    SweepFile { schema, batches }
}

impl SweepFile {
    pub(crate) fn rows(&self) -> usize {
        self.batches.iter().map(RecordBatch::num_rows).sum()
    }

    pub(crate) fn meta(&self, key: &str) -> Option<&str> {
        self.schema.metadata().get(key).map(String::as_str)
    }

    /// The values of column `name` (of array type `A`), over all batches.
    fn values<A: Array + 'static, T>(&self, name: &str, get: impl Fn(&A, usize) -> T) -> Vec<T> {
        let mut v = Vec::with_capacity(self.rows());
        for b in &self.batches {
            let col = b
                .column_by_name(name)
                .unwrap_or_else(|| panic!("no column {name}"));
            let a = col.as_any().downcast_ref::<A>().unwrap_or_else(|| {
                panic!(
                    "column {name} is {}, not the type expected",
                    col.data_type()
                )
            });
            assert_eq!(a.null_count(), 0, "nulls in column {name}");
            v.extend((0..a.len()).map(|i| get(a, i)));
        }
        v
    }

    pub(crate) fn f64s(&self, name: &str) -> Vec<f64> {
        self.values(name, |a: &Float64Array, i| a.value(i))
    }

    pub(crate) fn u64s(&self, name: &str) -> Vec<u64> {
        self.values(name, |a: &UInt64Array, i| a.value(i))
    }

    pub(crate) fn u32s(&self, name: &str) -> Vec<u32> {
        self.values(name, |a: &UInt32Array, i| a.value(i))
    }

    pub(crate) fn strings(&self, name: &str) -> Vec<String> {
        self.values(name, |a: &StringArray, i| a.value(i).to_string())
    }

    /// Outcome -> count in the file, zeros included.
    pub(crate) fn outcome_counts(&self) -> BTreeMap<String, u64> {
        let mut counts: BTreeMap<String, u64> = Outcome::ALL
            .iter()
            .map(|o| (o.name().to_string(), 0))
            .collect();
        for o in self.strings("outcome") {
            *counts.entry(o).or_default() += 1;
        }
        counts
    }
}

/// Checks what every sweep file must hold: `samples` rows numbered 0..samples in order,
/// the outcome counts of the summary, and its provenance.
fn check_sweep_file(path: &Path, summary: &Summary, seed: u64, scenario: &str) -> SweepFile {
    let file = read_sweep(path);
    let n = summary.samples;
    assert_eq!(file.rows() as u64, n, "rows of {}", path.display());
    assert!(
        file.u64s("sample").into_iter().eq(0..n),
        "{}: the sample column is not 0..{n} in order",
        path.display()
    );
    assert_eq!(
        file.outcome_counts(),
        summary.outcomes,
        "{}: the file's outcome counts differ from the summary's",
        path.display()
    );
    let n = n.to_string();
    let seed = seed.to_string();
    assert_eq!(file.meta("touchdown.samples"), Some(n.as_str()));
    assert_eq!(file.meta("touchdown.seed"), Some(seed.as_str()));
    // The scenario that ran, seed included.
    let ran = touchdown::scenario::with_seed(scenario, seed.parse().unwrap());
    assert_eq!(file.meta("touchdown.scenario"), Some(ran.as_str()));
    assert_eq!(file.meta("touchdown.kind"), Some("sweep"));
    let engine = file.meta("touchdown.engine").unwrap_or_default();
    assert!(
        engine.starts_with("touchdown "),
        "touchdown.engine = {engine:?}"
    );
    for f in file.schema.fields() {
        let unit = f.metadata().get("unit");
        assert!(
            unit.is_some_and(|u| !u.is_empty()),
            "{}: field {} has no unit",
            path.display(),
            f.name()
        );
    }
    file
}

// ---------------------------------------------------------------------------------------
// 1. Python readers.

/// Runs a sweep and `check_sweep.py` on its file.
fn check_sweep_with_python(dir: &TempDir, scenario: &str, seed: u64, format: &str, legs: usize) {
    let samples = 3000;
    let out = format!("sweep-{legs}-legs.{format}");
    let (seed_s, samples_s) = (seed.to_string(), samples.to_string());
    let args = [
        "--scenario",
        scenario,
        "--samples",
        &samples_s,
        "--seed",
        &seed_s,
        "--format",
        format,
        "--out",
        &out,
        "--quiet",
    ];
    let (_, s) = sweep(dir, &args);
    assert_eq!(s.samples, samples);
    let counts = s
        .outcomes
        .iter()
        .map(|(o, c)| format!("\"{o}\": {c}"))
        .collect::<Vec<_>>()
        .join(", ");
    run_python_check(
        "check_sweep.py",
        &[
            dir.join(&out).as_os_str(),
            format.as_ref(),
            samples_s.as_ref(),
            seed_s.as_ref(),
            legs.to_string().as_ref(),
            format!("{{{counts}}}").as_ref(),
        ],
        &format!("the sweep file of `touchdown sweep {}`", args.join(" ")),
    );
}

#[test]
fn python_readers_open_the_sweep() {
    if !python_readers_available("python_readers_open_the_sweep") {
        return;
    }
    let dir = TempDir::new("sweep-python");
    dir.write("short.toml", SHORT);
    dir.write("three-legs.toml", THREE_LEGS);
    check_sweep_with_python(&dir, "short.toml", 11, "arrow", 4);
    check_sweep_with_python(&dir, "short.toml", 11, "parquet", 4);
    check_sweep_with_python(&dir, "three-legs.toml", 12, "arrow", 3);
    check_sweep_with_python(&dir, "three-legs.toml", 12, "parquet", 3);
}

// ---------------------------------------------------------------------------------------
// 2. Determinism.

#[test]
fn sweeps_repeat_byte_for_byte_whatever_the_thread_count() {
    let dir = TempDir::new("sweep-threads");
    dir.write("short.toml", SHORT);
    // More samples than one thread's window of chunks (4 x 1024), so that one thread runs
    // two windows where two or three threads run one.
    let samples = "5000";
    let mut files = Vec::new();
    for format in ["arrow", "parquet"] {
        let mut first: Option<(String, Summary)> = None;
        for threads in ["1", "2", "3"] {
            let out = format!("t{threads}.{format}");
            let (b, s) = sweep(
                &dir,
                &[
                    "--scenario",
                    "short.toml",
                    "--samples",
                    samples,
                    "--seed",
                    "21",
                    "--threads",
                    threads,
                    "--format",
                    format,
                    "--out",
                    &out,
                ],
            );
            assert_eq!(b.threads.to_string(), threads);
            assert_eq!(s.wrote, out);
            match &first {
                None => {
                    check_sweep_file(&dir.join(&out), &s, 21, SHORT);
                    first = Some((out, s));
                }
                Some((first_out, first_s)) => {
                    assert_eq!(
                        s.outcomes, first_s.outcomes,
                        "outcomes of --threads {threads} and --threads 1 ({format})"
                    );
                    assert!(
                        read_bytes(&dir.join(&out)) == read_bytes(&dir.join(first_out)),
                        "--threads {threads} and --threads 1 wrote different {format} files"
                    );
                }
            }
        }
        files.push(dir.join(&format!("t1.{format}")));
    }

    // The Parquet file holds the same schema and data as the Arrow file.
    let (arrow, parquet) = (read_sweep(&files[0]), read_sweep(&files[1]));
    assert_eq!(arrow.schema.fields(), parquet.schema.fields());
    for (k, v) in arrow.schema.metadata() {
        assert_eq!(parquet.meta(k), Some(v.as_str()), "schema metadata {k}");
    }
    assert_eq!(arrow.batches.len(), parquet.batches.len());
    for (a, p) in arrow.batches.iter().zip(&parquet.batches) {
        for (f, (x, y)) in arrow
            .schema
            .fields()
            .iter()
            .zip(a.columns().iter().zip(p.columns()))
        {
            assert!(
                x == y,
                "column {} differs between the Arrow and Parquet files",
                f.name()
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// 3. Rows against traces.

/// The `terrain_tile N (offset U m, V m)` line of a trace's printout, as printed.
fn trace_terrain(run: &Run) -> Option<(u32, String, String)> {
    let line = run
        .stdout
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("terrain_tile "))?;
    let parse = || -> Option<(u32, String, String)> {
        let (tile, rest) = line.trim_start().split_once(" (offset ")?;
        let (u, v) = rest.strip_suffix(" m)")?.split_once(" m, ")?;
        Some((tile.parse().ok()?, u.to_string(), v.to_string()))
    };
    Some(parse().unwrap_or_else(|| panic!("cannot read the terrain line {line:?} of {run}")))
}

/// Checks that sweep rows hold the inputs and the outcome of `touchdown trace --sample i`
/// with the flags `source` (`--scenario F --seed S`, or `--sweep FILE`), and that the trace
/// stores the scenario text the sweep stored (seed included).
fn check_rows_against_traces(dir: &TempDir, source: &[&str], seed: &str, file: &SweepFile) {
    let rows = file.rows() as u64;
    let outcomes = file.strings("outcome");
    // The first samples, the last one, and the first of every outcome that occurs.
    let mut indices: BTreeSet<u64> = [0, 1, 2, rows - 1].into();
    for o in Outcome::ALL {
        if let Some(i) = outcomes.iter().position(|x| x == o.name()) {
            indices.insert(i as u64);
        }
    }
    let sample_seeds = file.u64s("sample_seed");
    let tiles = file.u32s("terrain_tile");
    let (offset_u, offset_v) = (
        file.f64s("terrain_offset_u_m"),
        file.f64s("terrain_offset_v_m"),
    );
    let inputs: Vec<Vec<f64>> = INPUT_FIELDS.iter().map(|(n, _)| file.f64s(n)).collect();

    let mut failures = Vec::new();
    for i in indices {
        let k = i as usize;
        let index = i.to_string();
        let out = format!("trace-{i}.arrow");
        let args = [
            &["trace"],
            source,
            &["--sample", &index, "--every", "1e9", "--out", &out],
        ]
        .concat();
        let run = touchdown(dir.path(), &args);
        run.assert_ok();
        let trace = read_sweep(&dir.join(&out)); // an Arrow IPC file too
        let meta = |key: &str| {
            trace
                .meta(key)
                .unwrap_or_else(|| panic!("trace {i} has no {key}"))
                .to_string()
        };
        let mut problems = Vec::new();
        if meta("touchdown.sample") != index || meta("touchdown.seed") != seed {
            problems.push(format!(
                "trace of sample {} of seed {}",
                meta("touchdown.sample"),
                meta("touchdown.seed")
            ));
        }
        if meta("touchdown.sample_seed") != sample_seeds[k].to_string() {
            problems.push(format!(
                "sample_seed: row {}, trace {}",
                sample_seeds[k],
                meta("touchdown.sample_seed")
            ));
        }
        for ((name, _), column) in INPUT_FIELDS.iter().zip(&inputs) {
            let text = meta(&format!("touchdown.input.{name}"));
            let traced: f64 = text
                .parse()
                .unwrap_or_else(|_| panic!("trace {i}: {name} = {text:?} is not a number"));
            if traced.to_bits() != column[k].to_bits() {
                problems.push(format!("{name}: row {:?}, trace {traced:?}", column[k]));
            }
        }
        if trace.meta("touchdown.scenario") != file.meta("touchdown.scenario") {
            problems.push(format!(
                "scenario text: sweep {:?}, trace {:?}",
                file.meta("touchdown.scenario"),
                trace.meta("touchdown.scenario")
            ));
        }
        if meta("touchdown.outcome") != outcomes[k] {
            problems.push(format!(
                "outcome: row (kernel) {}, trace (reference) {}",
                outcomes[k],
                meta("touchdown.outcome")
            ));
        }
        // The trace prints the terrain tile and offsets (to the mm) on rough terrain only.
        let row_terrain = (
            tiles[k],
            format!("{:.3}", offset_u[k]),
            format!("{:.3}", offset_v[k]),
        );
        match trace_terrain(&run) {
            Some(t) if t != row_terrain => {
                problems.push(format!("terrain: row {row_terrain:?}, trace {t:?}"));
            }
            None if (tiles[k], offset_u[k], offset_v[k]) != (0, 0.0, 0.0) => {
                problems.push(format!("terrain: row {row_terrain:?} on a flat surface"));
            }
            _ => {}
        }
        if !problems.is_empty() {
            failures.push(format!(
                "sample {i}:\n    {}\n{run}",
                problems.join("\n    ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "rows of the sweep (seed {seed}) differ from their traces `touchdown trace {}`:\n\n{}",
        source.join(" "),
        failures.join("\n\n")
    );
}

#[test]
fn rows_hold_the_inputs_and_outcomes_of_their_traces() {
    let dir = TempDir::new("sweep-vs-trace");
    for (name, text, seed, samples) in [
        ("short.toml", SHORT, "5", "3000"),
        ("rough.toml", ROUGH, "9", "2000"),
    ] {
        dir.write(name, text);
        let out = format!("{name}.arrow");
        let (_, s) = sweep(
            &dir,
            &[
                "--scenario",
                name,
                "--seed",
                seed,
                "--samples",
                samples,
                "--out",
                &out,
            ],
        );
        let file = check_sweep_file(&dir.join(&out), &s, seed.parse().unwrap(), text);
        // Traced from the scenario and seed, and from the sweep file alone.
        check_rows_against_traces(&dir, &["--scenario", name, "--seed", seed], seed, &file);
        check_rows_against_traces(&dir, &["--sweep", &out], seed, &file);
    }
}

// ---------------------------------------------------------------------------------------
// 4. Sample counts.

#[test]
fn sample_counts_in_any_notation_give_the_same_sweep() {
    let dir = TempDir::new("sweep-samples");
    dir.write("short.toml", SHORT);
    let run = |samples: &str, out: &str| {
        let (b, s) = sweep(
            &dir,
            &[
                "--scenario",
                "short.toml",
                "--samples",
                samples,
                "--seed",
                "4",
                "--out",
                out,
            ],
        );
        assert_eq!((b.samples, b.seed), (2500, 4));
        assert_eq!(s.samples, 2500, "the summary's `samples` line");
        check_sweep_file(&dir.join(out), &s, 4, SHORT);
        s
    };
    let plain = run("2500", "plain.arrow");
    let sci = run("2.5e3", "sci.arrow");
    assert_eq!(plain.outcomes, sci.outcomes);
    assert!(
        read_bytes(&dir.join("plain.arrow")) == read_bytes(&dir.join("sci.arrow")),
        "--samples 2.5e3 and --samples 2500 wrote different files"
    );

    // Without --samples, the scenario's `samples`; with it, the flag's.
    let text = format!("samples = 1200\n{SHORT}");
    dir.write("counted.toml", &text);
    let (b, s) = sweep(
        &dir,
        &["--scenario", "counted.toml", "--out", "default.arrow"],
    );
    assert_eq!((b.samples, s.samples), (1200, 1200));
    let default = check_sweep_file(&dir.join("default.arrow"), &s, 1, &text);
    let (b, s) = sweep(
        &dir,
        &[
            "--scenario",
            "counted.toml",
            "--samples",
            "700",
            "--out",
            "flag.arrow",
        ],
    );
    assert_eq!((b.samples, s.samples), (700, 700));
    let flag = check_sweep_file(&dir.join("flag.arrow"), &s, 1, &text);
    // Fewer samples of the same sweep: the first rows of the longer one.
    for (name, _) in INPUT_FIELDS {
        assert!(
            default.f64s(name)[..700] == flag.f64s(name)[..],
            "{name}: the 700 samples are not the first 700 of 1200"
        );
    }
    assert_eq!(
        default.strings("outcome")[..700],
        flag.strings("outcome")[..]
    );
}

// ---------------------------------------------------------------------------------------
// 5. No incomplete file under the final name.

#[test]
fn output_in_a_missing_folder_is_refused_before_any_work() {
    let dir = TempDir::new("sweep-missing-folder");
    dir.write("short.toml", SHORT);
    std::fs::create_dir(dir.join("present")).unwrap();
    for (out, folder) in [
        ("missing/sweep.arrow", "missing"),
        ("present/missing/sweep.parquet", "present/missing"),
    ] {
        let before = dir.entries();
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                "short.toml",
                "--samples",
                "2000",
                "--format",
                out.rsplit('.').next().unwrap(),
                "--out",
                out,
            ],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(
            run.stderr
                .contains(&format!("cannot write output file {out}"))
                && run
                    .stderr
                    .contains(&format!("folder {folder} does not exist")),
            "the message does not name the path: {run}"
        );
        assert!(
            !run.stderr.contains("touchdown sweep:"),
            "the sweep started: {run}"
        );
        assert!(run.stdout.is_empty(), "{run}");
        assert_eq!(dir.entries(), before, "{run}");
        assert!(
            std::fs::read_dir(dir.join("present"))
                .unwrap()
                .next()
                .is_none()
        );
    }
}

#[test]
fn finished_sweeps_leave_no_partial_file_and_failed_ones_leave_the_old_file() {
    let dir = TempDir::new("sweep-partial");
    dir.write("short.toml", SHORT);
    dir.write("bad.toml", "[lander]\nmass_kg = 0\n");
    // An existing file is replaced whole.
    dir.write("sweep.arrow", "an older file");
    for format in ["arrow", "parquet"] {
        let out = format!("sweep.{format}");
        let (_, s) = sweep(
            &dir,
            &[
                "--scenario",
                "short.toml",
                "--samples",
                "1500",
                "--format",
                format,
                "--out",
                &out,
            ],
        );
        check_sweep_file(&dir.join(&out), &s, 1, SHORT);
    }
    assert_eq!(
        dir.entries(),
        ["bad.toml", "short.toml", "sweep.arrow", "sweep.parquet"]
    );

    // A sweep refused leaves the file of the last one as it was.
    let before = read_bytes(&dir.join("sweep.arrow"));
    let run = touchdown(
        dir.path(),
        &["sweep", "--scenario", "bad.toml", "--out", "sweep.arrow"],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("`lander.mass_kg` = 0 "), "{run}");
    assert!(read_bytes(&dir.join("sweep.arrow")) == before);
    assert_eq!(
        dir.entries(),
        ["bad.toml", "short.toml", "sweep.arrow", "sweep.parquet"]
    );
}

/// Starts a sweep too long to finish (to `out` in `dir`) and kills it while it runs.
fn kill_a_running_sweep(dir: &TempDir, out: &str) {
    let mut child = Command::new(crate::common::BIN)
        .args([
            "sweep",
            "--scenario",
            "short.toml",
            "--samples",
            "1e9",
            "--threads",
            "1",
            "--quiet",
            "--out",
            out,
        ])
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start the touchdown binary");
    // The temporary file appears when the sweep starts; let it run a little more.
    let partial = dir.join(&format!("{out}.partial"));
    let start = Instant::now();
    while !partial.exists() && start.elapsed() < Duration::from_secs(30) {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the sweep ended early: {status}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let appeared = partial.exists();
    if appeared {
        std::thread::sleep(Duration::from_millis(300));
    }
    let still_running = child.try_wait().unwrap().is_none();
    child.kill().expect("kill the sweep");
    child.wait().expect("wait for the killed sweep");
    assert!(appeared, "no {} within 30 s", partial.display());
    assert!(still_running, "the sweep of 1e9 samples ended by itself");
}

#[test]
fn a_killed_sweep_leaves_no_file_under_its_name() {
    let dir = TempDir::new("sweep-killed");
    dir.write("short.toml", SHORT);
    kill_a_running_sweep(&dir, "new.arrow");
    assert!(
        !dir.join("new.arrow").exists(),
        "a killed sweep left a file under its final name"
    );
    dir.write("old.arrow", "an older file");
    kill_a_running_sweep(&dir, "old.arrow");
    assert!(
        read_bytes(&dir.join("old.arrow")) == b"an older file",
        "a killed sweep changed the file under its final name"
    );
}

// ---------------------------------------------------------------------------------------
// 6. Bad input.

const BAD_SWEEP_INPUTS: &[BadInput] = &[
    bad_args(
        "zero samples",
        &["--samples", "0"],
        &["--samples", "at least 1"],
    ),
    bad_args(
        "negative samples",
        &["--samples", "-5"],
        &["--samples", "'-5'", "not a whole number"],
    ),
    bad_args(
        "negative samples, with =",
        &["--samples=-5"],
        &["--samples", "'-5'", "not a whole number"],
    ),
    bad_args(
        "fractional samples",
        &["--samples", "1.5"],
        &["--samples", "'1.5'", "not a whole number"],
    ),
    bad_args(
        "samples not a number",
        &["--samples", "many"],
        &["--samples", "'many'", "not a whole number"],
    ),
    bad_args(
        "zero threads",
        &["--threads", "0"],
        &["--threads", "'0'", "at least 1"],
    ),
    bad_args(
        "negative threads",
        &["--threads", "-1"],
        &["--threads", "'-1'"],
    ),
    bad_args(
        "too many threads",
        &["--threads", "5000"],
        &["--threads", "'5000'", "at most 1024"],
    ),
    bad_args(
        "unknown format",
        &["--format", "csv"],
        &["--format", "'csv'", "arrow", "parquet"],
    ),
    bad_args("negative seed", &["--seed", "-1"], &["--seed", "'-1'"]),
    bad_args(
        "output where no file can be made",
        &["--out", "/proc/sweep.arrow"],
        &["cannot write output file /proc/sweep.arrow.partial"],
    ),
    bad_args(
        "output in a folder that is a file",
        &["--out", "/proc/self/status/sweep.arrow"],
        &["/proc/self/status is a file, not a folder"],
    ),
    bad_args(
        "resume with nothing to resume",
        &["--resume", "gone.arrow"],
        &["nothing to resume", "gone.arrow.interrupted"],
    ),
    bad_args(
        "resume with settings of its own",
        &["--resume", "gone.arrow", "--samples", "5"],
        &["--resume", "cannot be used with", "--samples"],
    ),
    bad_args(
        "shard index past the count",
        &["--shard", "4/4"],
        &["--shard", "\"4/4\"", "K from 0 to N-1"],
    ),
    bad_args(
        "zero shards",
        &["--shard", "0/0"],
        &["--shard", "\"0/0\"", "K from 0 to N-1"],
    ),
    bad_args(
        "shard not K/N",
        &["--shard", "2"],
        &["--shard", "\"2\"", "K from 0 to N-1"],
    ),
    bad_args(
        "seed beyond what a scenario file can hold",
        &["--seed", "9223372036854775808"],
        &["--seed", "at most 9223372036854775807"],
    ),
    bad_args(
        "a flag of trace",
        &["--every", "3"],
        &["unexpected argument '--every'"],
    ),
    bad_args(
        "output in a missing folder",
        &["--out", "missing/sweep.arrow"],
        &["missing/sweep.arrow", "folder missing does not exist"],
    ),
    bad_args(
        "output path that names no file",
        &["--out", "."],
        &["output path \".\"", "names no file"],
    ),
    bad_args(
        "missing scenario file",
        &["--scenario", "missing.toml"],
        &["cannot read scenario file missing.toml"],
    ),
    bad_scenario(
        "zero samples in the scenario",
        "samples = 0\n",
        &["`samples` = 0 ", "from 1 to"],
    ),
    bad_scenario(
        "bad scenario",
        "[lander]\nmass_kg = -5\n",
        &["`lander.mass_kg` = -5 ", "greater than 0"],
    ),
    bad_args(
        "resume naming the interrupted file",
        &["--resume", "b2.arrow.interrupted"],
        &[
            "--resume takes the output of the sweep",
            "touchdown sweep --resume b2.arrow",
        ],
    ),
    bad_args(
        "format contradicting the extension",
        &["--out", "x.parquet", "--format", "arrow"],
        &["--format arrow contradicts", "x.parquet", "a parquet file"],
    ),
    bad_args(
        "format contradicting the extension, the other way",
        &["--out", "x.feather", "--format", "parquet"],
        &["--format parquet contradicts", "x.feather", "an arrow file"],
    ),
    // Set-ups that defeat themselves: refused with the reason, before any work.
    bad_scenario(
        "a footpad above the CG",
        "[lander]\nleg_tips_m = [[0.4, 0.4, 0.1], [0.4, -0.4, -0.4], [-0.4, -0.4, -0.4], \
         [-0.4, 0.4, -0.4]]\n",
        &[
            "`lander.leg_tips_m`",
            "footpad 0 at [0.4, 0.4, 0.1]",
            "below the CG",
        ],
    ),
    bad_scenario(
        "footpads above the CG by a negative height",
        "[lander]\ncg_height_m = -0.2\n",
        &["`lander.cg_height_m`"],
    ),
    bad_scenario(
        "three footpads on a line",
        "[lander]\nleg_tips_m = [[0.4, 0.0, -0.4], [0.0, 0.0, -0.4], [-0.4, 0.0, -0.4]]\n",
        &["`lander.leg_tips_m`", "not on one line", "no area"],
    ),
    bad_scenario(
        "the CG beside the footpads",
        "[lander]\nleg_tips_m = [[0.4, 0.1, -0.4], [0.8, 0.1, -0.4], [0.6, 0.5, -0.4]]\n",
        &[
            "`lander.leg_tips_m`",
            "CG",
            "inside of their support polygon",
        ],
    ),
    bad_scenario(
        "struts pointing up with dampers on",
        "[damper]\nenabled = true\nstrut_axis = [0.0, 0.0, 1.0]\n",
        &["`damper.strut_axis` = [0, 0, 1]", "never stroke"],
    ),
    bad_scenario(
        "a hold time longer than the run",
        "[simulation]\nt_max_s = 1.5\n",
        &["`outcome.hold_time_s` = 2 s", "simulation.t_max_s = 1.5 s"],
    ),
    bad_scenario(
        "no gravity",
        "gravity_m_s2 = 0.0\n",
        &["`gravity_m_s2` = 0 ", "greater than 0"],
    ),
    bad_scenario(
        "a run too short to reach the surface",
        "[initial]\nclearance_m = 5.0\n\n[simulation]\nt_max_s = 3.0\n",
        &[
            "`simulation.t_max_s` = 3 s",
            "reach the surface",
            "clearance_m = 5 m",
        ],
    ),
    bad_scenario(
        "a descent start without a descent law",
        "[initial]\nstart = \"descent\"\n",
        &["`initial.start` = \"descent\"", "[control.descent]"],
    ),
    bad_scenario(
        "a descent law without a descent start",
        concat!(
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.descent]\n",
        ),
        &["`control.descent`", "initial.start = \"descent\""],
    ),
    bad_scenario(
        "a descent braking harder than the thrusters can",
        concat!(
            "[initial]\nstart = \"descent\"\n",
            "[[thrusters]]\nposition_m = [0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[[thrusters]]\nposition_m = [-0.4, 0.0, 0.3]\ndirection = [0.0, 0.0, 1.0]\n",
            "max_thrust_n = 2.0\nmin_on_time_s = 0.01\n",
            "[control]\n[control.descent]\nbraking_m_s2 = 0.05\n",
        ),
        &[
            "`control.descent.braking_m_s2` = up to 0.05",
            "6.6800 N along +Z_B",
            "at most 4.0000 N",
        ],
    ),
    BadInput {
        name: "bad scenario with an explicit output path and format",
        scenario: Some("[lander]\nmass_kg = 0\n"),
        args: &["--out", "explicit.parquet", "--format", "parquet"],
        expect: &["`lander.mass_kg` = 0 "],
    },
];

#[test]
fn bad_sweep_input_is_refused_before_any_work() {
    let failures: Vec<String> = BAD_SWEEP_INPUTS
        .iter()
        .flat_map(|case| check_bad_input("sweep", case, &["touchdown sweep:"]))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs were not refused properly:\n\n{}",
        failures.len(),
        BAD_SWEEP_INPUTS.len(),
        failures.join("\n\n")
    );
}

/// A full disk, simulated by a file size limit (and SIGXFSZ ignored, as a full disk sends
/// no signal): the write fails, the sweep says which file and why, exits 2 and leaves no
/// file behind.
#[test]
fn a_full_disk_is_reported_and_leaves_no_file() {
    let dir = TempDir::new("sweep-full-disk");
    dir.write("short.toml", SHORT);
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 512; exec {} sweep --scenario short.toml --samples 20000 \\
             --quiet --out full.arrow",
            crate::common::BIN
        ))
        .current_dir(dir.path())
        .output()
        .expect("run sh");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        stderr.contains("cannot write output file full.arrow.partial")
            && stderr.contains("File too large"),
        "stderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "stderr: {stderr}");
    assert_eq!(dir.entries(), ["short.toml"]);
}
