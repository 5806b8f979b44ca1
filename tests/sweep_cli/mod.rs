//! End-to-end tests of `touchdown sweep`: the binary run as a user runs it, its file read
//! back in Rust and in Python, against its closing summary and against `touchdown trace`.
//!
//! Every sweep is small (a few thousand samples of a scenario cut at 20 s) so that the
//! whole folder runs in seconds. Every test works in a fresh folder of its own under the
//! system temp folder, removed when the test passes and kept when it fails.

use crate::common::{Run, TempDir, read_bytes, touchdown};
use arrow_array::{Array, Float64Array, RecordBatch, UInt32Array, UInt64Array};
use arrow_ipc::reader::FileReader;
use arrow_schema::SchemaRef;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use touchdown::reference::Outcome;

mod bad_input;
mod determinism;
mod final_name;
mod python_readers;
mod sample_counts;
mod traces;

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
    // `held` is listed for sweeps with a control loop only.
    let all: BTreeSet<&str> = Outcome::listed(names.contains("held"))
        .map(Outcome::name)
        .collect();
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
        crate::common::batch_texts(&self.batches, name)
    }

    /// Outcome -> count in the file, zeros included (but `held`'s, listed only for sweeps
    /// with a control loop, where it occurs).
    pub(crate) fn outcome_counts(&self) -> BTreeMap<String, u64> {
        let mut counts: BTreeMap<String, u64> = Outcome::listed(false)
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
