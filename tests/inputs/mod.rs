//! The user's own inputs, `touchdown sweep --inputs TABLE`: a table of a sweep's input
//! columns, replayed, gives that sweep's rows (every column, bit for bit), in CSV, Arrow and
//! Parquet, in any row order given the seeds; values the table does not give are drawn as
//! the scenario draws them; shards, merge, threads and `--keep-columns` behave as for any
//! sweep; bad tables are refused before any work, naming row and column.

use crate::common::read_bytes;
use arrow_array::{Array, Float64Array, RecordBatch, StringArray, UInt64Array};
use arrow_schema::{Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::path::Path;
use std::sync::Arc;
use touchdown::scenario::{INPUT_FIELDS, PARAMETER_FIELDS};

mod bad_tables;
mod readme;
mod replay;
mod shards;

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
