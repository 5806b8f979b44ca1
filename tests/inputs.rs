//! The user's own inputs, `touchdown sweep --inputs TABLE`: a table of a sweep's input
//! columns, replayed, gives that sweep's rows (every column, bit for bit), in CSV, Arrow and
//! Parquet, in any row order given the seeds; values the table does not give are drawn as
//! the scenario draws them; shards, merge, threads and `--keep-columns` behave as for any
//! sweep; bad tables are refused before any work, naming row and column.

use crate::common::{TempDir, read_bytes, touchdown};
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, StringArray, UInt64Array};
use arrow_schema::{Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::path::Path;
use std::sync::Arc;
use touchdown::scenario::{INPUT_FIELDS, PARAMETER_FIELDS};

/// A rough surface of uncertain regolith, a lander of uncertain mass, crushing dampers:
/// every kind of value a table can give (inputs, parameters, terrain), several outcomes.
const SCENARIO: &str = "[lander]
mass_kg = { dist = \"uniform\", min = 80.0, max = 120.0 }
[surface]
friction_coefficient = { dist = \"uniform\", min = 0.3, max = 0.9 }
damping_n_s_per_m = { dist = \"uniform\", min = 200.0, max = 2000.0 }
[surface.roughness]
rms_height_m = { dist = \"uniform\", min = 0.0, max = 0.03 }
node_spacing_m = 0.05
smoothing_length_m = 0.15
tile_size_m = 3.2
tiles = 3
[damper]
enabled = true
[simulation]
t_max_s = 15.0
";

/// A sweep file (Arrow or Parquet) as one batch, with its schema's metadata.
fn read_sweep(path: &Path) -> RecordBatch {
    let file = std::fs::File::open(path).unwrap();
    let (schema, batches): (_, Vec<RecordBatch>) = if read_bytes(path).starts_with(b"PAR1") {
        let b = ParquetRecordBatchReaderBuilder::try_new(file).unwrap();
        let schema = b.schema().clone();
        (
            schema,
            b.build().unwrap().collect::<Result<_, _>>().unwrap(),
        )
    } else {
        let r = arrow_ipc::reader::FileReader::try_new(file, None).unwrap();
        let schema = r.schema();
        (schema, r.collect::<Result<_, _>>().unwrap())
    };
    arrow_select::concat::concat_batches(&schema, &batches).unwrap()
}

/// The columns `names` of `b`.
fn select(b: &RecordBatch, names: &[&str]) -> RecordBatch {
    let fields: Vec<Field> = names
        .iter()
        .map(|n| b.schema().field_with_name(n).unwrap().clone())
        .collect();
    let columns = names
        .iter()
        .map(|n| b.column_by_name(n).unwrap().clone())
        .collect();
    RecordBatch::try_new(Arc::new(Schema::new(fields)), columns).unwrap()
}

/// Rows `rows` of `b`, in that order.
fn take(b: &RecordBatch, rows: &[u64]) -> RecordBatch {
    let indices = UInt64Array::from(rows.to_vec());
    arrow_select::take::take_record_batch(b, &indices).unwrap()
}

/// `b` as CSV, numbers written in Rust's shortest form that reads back to the same bits.
fn write_csv(path: &Path, b: &RecordBatch) {
    let mut text = b
        .schema()
        .fields()
        .iter()
        .map(|f| f.name().clone())
        .collect::<Vec<_>>()
        .join(",");
    text.push('\n');
    for row in 0..b.num_rows() {
        let cells: Vec<String> = b
            .columns()
            .iter()
            .map(|c| {
                if let Some(x) = c.as_any().downcast_ref::<Float64Array>() {
                    format!("{:?}", x.value(row))
                } else if let Some(x) = c.as_any().downcast_ref::<UInt64Array>() {
                    x.value(row).to_string()
                } else if let Some(x) = c.as_any().downcast_ref::<arrow_array::UInt32Array>() {
                    x.value(row).to_string()
                } else if let Some(x) = c.as_any().downcast_ref::<StringArray>() {
                    x.value(row).to_string()
                } else {
                    panic!("no CSV form for {:?}", c.data_type())
                }
            })
            .collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    std::fs::write(path, text).unwrap();
}

fn write_arrow(path: &Path, b: &RecordBatch) {
    let file = std::fs::File::create(path).unwrap();
    let mut w = arrow_ipc::writer::FileWriter::try_new(file, &b.schema()).unwrap();
    // In two batches, as a table written in pieces comes.
    let half = b.num_rows() / 2;
    w.write(&b.slice(0, half)).unwrap();
    w.write(&b.slice(half, b.num_rows() - half)).unwrap();
    w.finish().unwrap();
}

fn write_parquet(path: &Path, b: &RecordBatch) {
    let file = std::fs::File::create(path).unwrap();
    let mut w = ArrowWriter::try_new(file, b.schema(), None).unwrap();
    w.write(b).unwrap();
    w.close().unwrap();
}

/// Asserts that `b` has every column of `a` but `except` with the same values (bit for
/// bit), and says which differ.
fn assert_same_columns(a: &RecordBatch, b: &RecordBatch, except: &[&str], what: &str) {
    assert_eq!(a.num_rows(), b.num_rows(), "{what}: rows");
    let mut differ = Vec::new();
    for f in a.schema().fields() {
        if except.contains(&f.name().as_str()) {
            continue;
        }
        let x = a.column_by_name(f.name()).unwrap();
        match b.column_by_name(f.name()) {
            Some(y) if x.to_data() == y.to_data() => {}
            Some(_) => differ.push(f.name().clone()),
            None => differ.push(format!("{} (missing)", f.name())),
        }
    }
    assert!(differ.is_empty(), "{what}: columns differ: {differ:?}");
}

/// The sweep's input columns that a table of its draws gives: the 12 inputs and the
/// parameters it draws.
fn input_columns(a: &RecordBatch) -> Vec<&'static str> {
    INPUT_FIELDS
        .iter()
        .chain(PARAMETER_FIELDS.iter())
        .map(|(n, _)| *n)
        .filter(|n| a.column_by_name(n).is_some())
        .collect()
}

fn metadata(path: &Path, key: &str) -> Option<String> {
    read_sweep(path).schema().metadata().get(key).cloned()
}

#[test]
fn a_replayed_table_gives_the_rows_of_the_sweep_it_came_from() {
    let dir = TempDir::new("inputs-replay");
    dir.write("s.toml", SCENARIO);
    let sweep = |args: &[&str]| {
        let run = touchdown(
            dir.path(),
            &[&["sweep", "--scenario", "s.toml", "--quiet"], args].concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
    };
    sweep(&["--samples", "600", "--out", "a.arrow"]);
    let a = read_sweep(&dir.join("a.arrow"));
    let outcomes = a
        .column_by_name("outcome")
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap()
        .iter()
        .flatten()
        .collect::<std::collections::BTreeSet<_>>();
    assert!(outcomes.len() >= 2, "one outcome only: {outcomes:?}");
    let names = input_columns(&a);
    // The 12 inputs and the 4 drawn parameters.
    assert_eq!(names.len(), 16, "{names:?}");
    let table = select(&a, &names);
    write_csv(&dir.join("in.csv"), &table);
    write_arrow(&dir.join("in.arrow"), &table);
    write_parquet(&dir.join("in.parquet"), &table);
    for (t, out) in [
        ("in.csv", "b.arrow"),
        ("in.arrow", "c.arrow"),
        ("in.parquet", "d.parquet"),
    ] {
        sweep(&["--inputs", t, "--out", out]);
        let b = read_sweep(&dir.join(out));
        // Every column: sample, seed, inputs, terrain, every result, the parameters.
        assert_eq!(b.num_columns(), a.num_columns());
        assert_same_columns(&a, &b, &[], &format!("{t} replayed"));
        assert_eq!(
            metadata(&dir.join(out), "touchdown.inputs.sha256").as_deref(),
            Some(touchdown::table::sha256_hex(&read_bytes(&dir.join(t))).as_str()),
            "{t}: the table's SHA-256 in the file's metadata"
        );
    }

    // Some rows, backwards, with their seeds and terrain: each replayed row is the row it
    // came from (but for its place, the `sample` column).
    let rows: Vec<u64> = (0..600).rev().step_by(7).collect();
    let with_seeds = [
        &["sample_seed"][..],
        &names,
        &["terrain_tile", "terrain_offset_u_m", "terrain_offset_v_m"],
    ]
    .concat();
    write_csv(
        &dir.join("some.csv"),
        &take(&select(&a, &with_seeds), &rows),
    );
    sweep(&["--inputs", "some.csv", "--out", "some.arrow"]);
    let some = read_sweep(&dir.join("some.arrow"));
    assert_same_columns(&take(&a, &rows), &some, &["sample"], "rows backwards");
    let samples = some.column_by_name("sample").unwrap();
    let expected: ArrayRef = Arc::new(UInt64Array::from_iter_values(0..rows.len() as u64));
    assert_eq!(samples.to_data(), expected.to_data());

    // A trace of a row runs its table's values: the row's seed, inputs and parameters.
    let run = touchdown(
        dir.path(),
        &[
            "trace",
            "--sweep",
            "some.arrow",
            "--sample",
            "3",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let trace_meta = |k: &str| {
        let r = arrow_ipc::reader::FileReader::try_new(
            std::fs::File::open(dir.join("t.arrow")).unwrap(),
            None,
        )
        .unwrap();
        r.schema().metadata().get(k).cloned().unwrap()
    };
    let f64_at = |b: &RecordBatch, name: &str, row: usize| {
        b.column_by_name(name)
            .unwrap()
            .as_any()
            .downcast_ref::<Float64Array>()
            .unwrap()
            .value(row)
    };
    let source = rows[3] as usize;
    let seed = a
        .column_by_name("sample_seed")
        .unwrap()
        .as_any()
        .downcast_ref::<UInt64Array>()
        .unwrap()
        .value(source);
    assert_eq!(trace_meta("touchdown.sample_seed"), seed.to_string());
    for name in ["slope_deg", "yaw_deg"] {
        assert_eq!(
            trace_meta(&format!("touchdown.input.{name}")),
            f64_at(&a, name, source).to_string()
        );
    }
    assert_eq!(
        trace_meta("touchdown.parameter.friction_coefficient"),
        f64_at(&a, "friction_coefficient", source).to_string()
    );
    let outcome = a
        .column_by_name("outcome")
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap()
        .value(source);
    assert_eq!(trace_meta("touchdown.outcome"), outcome);
}

#[test]
fn values_a_table_does_not_give_are_drawn_as_the_scenario_draws_them() {
    // A table that gives every sample a 10 deg slope and nothing else runs as the scenario
    // with the slope fixed at 10 deg: the other inputs, the parameters and the terrain are
    // drawn by row index, as without a table (common random numbers).
    let dir = TempDir::new("inputs-partial");
    dir.write("s.toml", SCENARIO);
    dir.write(
        "fixed.toml",
        &format!("{SCENARIO}[inputs]\nslope_deg = 10.0\n"),
    );
    dir.write("slope.csv", &format!("slope_deg\n{}", "10\n".repeat(300)));
    for (args, out) in [
        (
            &["--scenario", "s.toml", "--inputs", "slope.csv"][..],
            "table.arrow",
        ),
        (
            &["--scenario", "fixed.toml", "--samples", "300"],
            "fixed.arrow",
        ),
    ] {
        let run = touchdown(
            dir.path(),
            &[&["sweep", "--quiet", "--out", out], args].concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
    }
    let (t, f) = (
        read_sweep(&dir.join("table.arrow")),
        read_sweep(&dir.join("fixed.arrow")),
    );
    assert_same_columns(&f, &t, &[], "slope from the table against slope fixed");
}

/// A table of 5,000 samples of the default scenario with two columns the sweep does not
/// know: a label and a weight.
fn labelled_table(dir: &TempDir) {
    let mut text = String::from("slope_deg,case,yaw_deg,weight\n");
    for i in 0..5000 {
        let slope = f64::from(i % 400) * 0.1;
        let yaw = f64::from(i * 37 % 360);
        text.push_str(&format!(
            "{slope},case {},{yaw},{}\n",
            i % 3,
            0.5 + f64::from(i % 5)
        ));
    }
    dir.write("in.csv", &text);
}

#[test]
fn table_sweeps_shard_merge_and_keep_columns_like_any_sweep() {
    let dir = TempDir::new("inputs-shards");
    labelled_table(&dir);
    dir.write("s.toml", "[simulation]\nt_max_s = 10.0\n");
    let sweep = |args: &[&str]| {
        let run = touchdown(
            dir.path(),
            &[
                &[
                    "sweep",
                    "--scenario",
                    "s.toml",
                    "--inputs",
                    "in.csv",
                    "--quiet",
                ],
                args,
            ]
            .concat(),
        );
        assert_eq!(run.code, Some(0), "{run}");
        run
    };
    // Unknown columns are refused by name without --keep-columns.
    let run = touchdown(
        dir.path(),
        &["sweep", "--inputs", "in.csv", "--out", "x.arrow"],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("unknown column case"), "{run}");
    assert!(!dir.join("x.arrow").exists());

    sweep(&["--keep-columns", "--out", "one.arrow", "--threads", "1"]);
    sweep(&["--keep-columns", "--out", "two.arrow", "--threads", "2"]);
    assert!(
        read_bytes(&dir.join("one.arrow")) == read_bytes(&dir.join("two.arrow")),
        "1 and 2 threads give different files"
    );
    let one = read_sweep(&dir.join("one.arrow"));
    assert_eq!(one.num_rows(), 5000);
    // The kept columns come last, as the table has them.
    let fields = one.schema().fields().clone();
    let last: Vec<&str> = fields[fields.len() - 2..]
        .iter()
        .map(|f| f.name().as_str())
        .collect();
    assert_eq!(last, ["case", "weight"]);
    let case = one
        .column_by_name("case")
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap();
    let weight = one
        .column_by_name("weight")
        .unwrap()
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap();
    let slope = one
        .column_by_name("slope_deg")
        .unwrap()
        .as_any()
        .downcast_ref::<Float64Array>()
        .unwrap();
    for i in 0..5000 {
        assert_eq!(case.value(i), format!("case {}", i % 3));
        assert_eq!(weight.value(i), 0.5 + (i % 5) as f64);
        assert_eq!(slope.value(i), (i % 400) as f64 * 0.1);
    }

    // Three shards merged: the file of one process, byte for byte; in Parquet too.
    for k in 0..3 {
        sweep(&[
            "--keep-columns",
            "--shard",
            &format!("{k}/3"),
            "--out",
            &format!("s{k}.arrow"),
        ]);
    }
    let run = touchdown(
        dir.path(),
        &[
            "merge",
            "s2.arrow",
            "s0.arrow",
            "s1.arrow",
            "--out",
            "merged.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    assert!(
        read_bytes(&dir.join("merged.arrow")) == read_bytes(&dir.join("one.arrow")),
        "merged shards differ from one process"
    );
    sweep(&["--keep-columns", "--out", "one.parquet"]);
    assert_same_columns(&one, &read_sweep(&dir.join("one.parquet")), &[], "Parquet");

    // --samples N runs the first N rows.
    sweep(&["--keep-columns", "--samples", "100", "--out", "first.arrow"]);
    let first = read_sweep(&dir.join("first.arrow"));
    assert_same_columns(&one.slice(0, 100), &first, &[], "the first 100 rows");

    // Shards of another table (one changed value) do not merge.
    let text = std::fs::read_to_string(dir.join("in.csv")).unwrap();
    dir.write("in.csv", &text.replacen("case 0", "case 9", 1));
    sweep(&["--keep-columns", "--shard", "0/3", "--out", "other0.arrow"]);
    let run = touchdown(
        dir.path(),
        &[
            "merge",
            "other0.arrow",
            "s1.arrow",
            "s2.arrow",
            "--out",
            "m2.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("table of inputs"), "{run}");
    assert!(!dir.join("m2.arrow").exists());
    // Nor does a trace of the first sweep take the changed table.
    let run = touchdown(
        dir.path(),
        &[
            "trace",
            "--sweep",
            "one.arrow",
            "--sample",
            "1",
            "--out",
            "t.arrow",
        ],
    );
    assert_eq!(run.code, Some(2), "{run}");
    assert!(run.stderr.contains("is not the table of inputs"), "{run}");
    assert!(!dir.join("t.arrow").exists());
}

/// One bad table: its file name and bytes, further arguments, and what the error says.
struct BadTable {
    name: &'static str,
    file: &'static str,
    bytes: Vec<u8>,
    args: &'static [&'static str],
    expect: &'static [&'static str],
}

fn csv(name: &'static str, text: &str, expect: &'static [&'static str]) -> BadTable {
    BadTable {
        name,
        file: "in.csv",
        bytes: text.as_bytes().to_vec(),
        args: &[],
        expect,
    }
}

fn parquet(name: &'static str, b: &RecordBatch, expect: &'static [&'static str]) -> BadTable {
    let mut bytes = Vec::new();
    let mut w = ArrowWriter::try_new(&mut bytes, b.schema(), None).unwrap();
    w.write(b).unwrap();
    w.close().unwrap();
    BadTable {
        name,
        file: "in.parquet",
        bytes,
        args: &[],
        expect,
    }
}

fn one_column(name: &str, a: ArrayRef) -> RecordBatch {
    RecordBatch::try_new(
        Arc::new(Schema::new(vec![Field::new(
            name,
            a.data_type().clone(),
            true,
        )])),
        vec![a],
    )
    .unwrap()
}

#[test]
fn bad_tables_are_refused_before_any_work_naming_row_and_column() {
    let mut cases = vec![
        csv(
            "not a number",
            "slope_deg,yaw_deg\n1,2\n3,4\nabc,5\n",
            &[
                "in.csv: row 2 (line 4), column slope_deg",
                "\"abc\" is not a number",
            ],
        ),
        csv(
            "NaN",
            "slope_deg,yaw_deg\n1,2\n3,NaN\n",
            &[
                "row 1 (line 3), column yaw_deg",
                "NaN is not a finite number",
            ],
        ),
        csv(
            "empty cell",
            "slope_deg,yaw_deg\n1,2\n,4\n",
            &["row 1 (line 3), column slope_deg", "empty"],
        ),
        csv(
            "slope out of range",
            "slope_deg\n10\n20\n95\n",
            &[
                "row 2 (line 4), column slope_deg",
                "95 is out of range",
                "90 deg",
            ],
        ),
        csv(
            "negative friction",
            "friction_coefficient\n0.5\n-0.1\n",
            &["row 1 (line 3), column friction_coefficient", "at least 0"],
        ),
        csv(
            "zero mass",
            "mass_kg\n0\n",
            &["row 0 (line 2), column mass_kg", "greater than 0"],
        ),
        csv(
            "unknown column",
            "slope_deg,slop_deg\n1,2\n",
            &["unknown column slop_deg", "--keep-columns"],
        ),
        csv(
            "a result column",
            "slope_deg,outcome\n1,stable\n",
            &["column outcome is a result of a sweep"],
        ),
        csv(
            "a column twice",
            "slope_deg,yaw_deg,slope_deg\n1,2,3\n",
            &["column slope_deg appears twice"],
        ),
        csv(
            "sample numbers not the rows",
            "sample,slope_deg\n0,1\n5,2\n",
            &["row 1 (line 3), column sample", "holds 5"],
        ),
        csv(
            "a row too short",
            "slope_deg,yaw_deg\n1,2\n3\n",
            &["line 3 has 1 fields, the header 2"],
        ),
        csv("no rows", "slope_deg,yaw_deg\n", &["the table has no rows"]),
        csv(
            "a blank line (an empty value in a one-column table)",
            "slope_deg\n1\n\n3\n",
            &["in.csv: line 3 is blank"],
        ),
        csv(
            "a seed written as a float",
            "sample_seed\n12.5\n",
            &["column sample_seed", "not a whole number"],
        ),
        csv(
            "a seed below 0",
            "sample_seed\n-1\n",
            &["column sample_seed", "-1 is not a seed"],
        ),
        csv(
            "a terrain tile on a flat surface",
            "terrain_tile\n0\n2\n",
            &["row 1, column terrain_tile", "the surface is flat"],
        ),
        csv(
            "a crush strength without dampers",
            "crush_strength_psi\n10\n",
            &[
                "column crush_strength_psi (damper.crush_strength_psi)",
                "damper.enabled = false",
            ],
        ),
        parquet(
            "text in a Parquet column",
            &one_column(
                "slope_deg",
                Arc::new(StringArray::from(vec!["1.0", "steep"])),
            ),
            &[
                "in.parquet: row 1, column slope_deg",
                "\"steep\" is not a number",
            ],
        ),
        parquet(
            "booleans in a Parquet column",
            &one_column(
                "yaw_deg",
                Arc::new(arrow_array::BooleanArray::from(vec![true, false])),
            ),
            &["column yaw_deg is of type Boolean"],
        ),
        parquet(
            "a null in a Parquet column",
            &one_column(
                "yaw_deg",
                Arc::new(Float64Array::from(vec![Some(1.0), None, Some(2.0)])),
            ),
            &["in.parquet: row 1, column yaw_deg", "empty"],
        ),
    ];
    cases.push(BadTable {
        args: &["--samples", "3"],
        ..csv(
            "more samples than rows",
            "slope_deg\n1\n2\n",
            &["--samples 3", "has 2 rows"],
        )
    });
    cases.push(BadTable {
        args: &["--design", "sobol-indices"],
        ..csv(
            "Saltelli's design",
            "slope_deg\n1\n2\n",
            &["sobol-indices", "a table gives each sample its own row"],
        )
    });
    cases.push(BadTable {
        file: "in.bin",
        bytes: vec![0x80, 0x81, 0x00, 0x01],
        ..csv(
            "not a table",
            "",
            &["in.bin is neither Parquet, Arrow nor CSV"],
        )
    });

    let mut problems = Vec::new();
    for case in &cases {
        let dir = TempDir::new("bad-table");
        std::fs::write(dir.join(case.file), &case.bytes).unwrap();
        let before = dir.entries();
        let run = touchdown(
            dir.path(),
            &[
                &["sweep", "--inputs", case.file, "--out", "out.arrow"],
                case.args,
            ]
            .concat(),
        );
        let mut wrong = Vec::new();
        if run.code != Some(2) {
            wrong.push(format!("exit code {:?}", run.code));
        }
        for s in case.expect {
            if !run.stderr.contains(s) {
                wrong.push(format!("stderr lacks {s:?}"));
            }
        }
        for s in ["panicked", "touchdown sweep:"] {
            if run.stderr.contains(s) {
                wrong.push(format!("stderr has {s:?}"));
            }
        }
        if dir.entries() != before {
            wrong.push(format!("files: {:?}", dir.entries()));
        }
        if !wrong.is_empty() {
            problems.push(format!("{}: {}\n{run}", case.name, wrong.join("; ")));
        }
    }
    // A missing table, and --keep-columns without a table.
    let dir = TempDir::new("bad-table");
    for (args, expect) in [
        (
            &["sweep", "--inputs", "none.csv"][..],
            "cannot read the input table none.csv",
        ),
        (&["sweep", "--keep-columns"], "--inputs"),
    ] {
        let run = touchdown(dir.path(), args);
        if run.code != Some(2) || !run.stderr.contains(expect) {
            problems.push(format!("{args:?}: expected exit 2 and {expect:?}\n{run}"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

/// The `sh` block of the README's section `heading`.
fn readme_block(heading: &str) -> String {
    let readme = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md"))
        .expect("README.md");
    let section = readme
        .split(&format!("\n{heading}\n"))
        .nth(1)
        .unwrap_or_else(|| panic!("no section {heading} in the README"));
    let block = section
        .split("```sh\n")
        .nth(1)
        .and_then(|b| b.split("\n```").next())
        .unwrap_or_else(|| panic!("no sh block in the README's {heading}"));
    block.to_string()
}

#[test]
fn the_readme_python_lines_make_tables_that_replay() {
    if !crate::common::python_readers_available("the_readme_python_lines_make_tables_that_replay") {
        return;
    }
    let dir = TempDir::new("inputs-readme");
    // `python3` and `touchdown` as the README's lines call them: the tests' environment
    // and this build.
    let bin = dir.join("bin");
    std::fs::create_dir(&bin).unwrap();
    // A script, not a link: a virtual environment's interpreter knows it by its own path.
    let script = bin.join("python3");
    std::fs::write(
        &script,
        format!("#!/bin/sh\nexec '{}' \"$@\"\n", crate::common::python()),
    )
    .unwrap();
    std::fs::set_permissions(&script, std::os::unix::fs::PermissionsExt::from_mode(0o755)).unwrap();
    std::os::unix::fs::symlink(crate::common::BIN, bin.join("touchdown")).unwrap();
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--samples",
            "3000",
            "--quiet",
            "--out",
            "sweep.arrow",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    // The "changed" scenario of the example is the default one here, so that the tipped
    // landers tip again, exactly.
    dir.write("changed.toml", "# the default scenario\n");
    let block = readme_block("### Your own inputs");
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let o = std::process::Command::new("sh")
        .args(["-e", "-c", &block])
        .current_dir(dir.path())
        .env("PATH", path)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "the README's lines failed:\n{block}\n--- stdout ---\n{}\n--- stderr ---\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let gnc = read_sweep(&dir.join("gnc.arrow"));
    assert_eq!(gnc.num_rows(), 500);
    assert_eq!(
        metadata(&dir.join("gnc.arrow"), "touchdown.inputs.columns").as_deref(),
        Some("roll_deg,pitch_deg,velocity_error_z_m_s")
    );
    // Tipped again, every one, with the same results.
    let whole = read_sweep(&dir.join("sweep.arrow"));
    let outcome = whole
        .column_by_name("outcome")
        .unwrap()
        .as_any()
        .downcast_ref::<StringArray>()
        .unwrap();
    let tipped: Vec<u64> = (0..whole.num_rows())
        .filter(|&i| outcome.value(i) == "tipped")
        .map(|i| i as u64)
        .collect();
    assert!(tipped.len() > 100, "{} tipped", tipped.len());
    let again = read_sweep(&dir.join("tipped-again.arrow"));
    assert_same_columns(&take(&whole, &tipped), &again, &["sample"], "tipped again");
}
