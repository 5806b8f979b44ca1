//! Reading files of touchdown back, whole batches as written: Arrow IPC or Parquet, told
//! apart by their first bytes, with the schema metadata they were written with (for
//! `merge`, `--resume` and the readers of columns: `sweep::SweepFile`, `columns::Table`).

use super::format::{BATCH_ROWS, Format};
use crate::reference::Outcome;
use anyhow::{anyhow, bail};
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

/// The format of a file, from its first bytes.
pub fn format_of(path: &Path) -> anyhow::Result<Format> {
    let mut head = [0u8; 6];
    let n = File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .map_err(|e| anyhow!("cannot read {}: {e}", path.display()))?;
    match &head[..n] {
        [b'A', b'R', b'R', b'O', b'W', b'1'] => Ok(Format::Arrow),
        [b'P', b'A', b'R', b'1', ..] => Ok(Format::Parquet),
        _ => bail!(
            "{} is neither an Arrow IPC file nor a Parquet file",
            path.display()
        ),
    }
}

/// The batches of a file, and its schema with the metadata it was written with.
pub fn open(path: &Path, format: Format) -> anyhow::Result<(SchemaRef, Batches)> {
    let context = |e: &dyn std::fmt::Display| anyhow!("cannot read {}: {e}", path.display());
    let file = File::open(path).map_err(|e| context(&e))?;
    Ok(match format {
        Format::Arrow => {
            let r = arrow_ipc::reader::FileReader::try_new(BufReader::new(file), None)
                .map_err(|e| context(&e))?;
            (r.schema(), Box::new(r))
        }
        Format::Parquet => {
            // The reader's own batches carry no schema metadata: take the builder's schema.
            let b = ParquetRecordBatchReaderBuilder::try_new(file).map_err(|e| context(&e))?;
            let schema = b.schema().clone();
            let r = b
                .with_batch_size(BATCH_ROWS)
                .build()
                .map_err(|e| context(&e))?;
            (schema, Box::new(r))
        }
    })
}

/// The outcome named `name` in the outcome column of the file at `path`.
pub fn outcome_of(name: &str, path: &Path) -> anyhow::Result<Outcome> {
    Outcome::from_name(name).ok_or_else(|| anyhow!("{}: unknown outcome {name:?}", path.display()))
}

/// Record batches as a reader yields them.
pub type Batches = Box<dyn Iterator<Item = Result<RecordBatch, arrow_schema::ArrowError>>>;
