//! Reading files of touchdown back, whole batches as written: Arrow IPC or Parquet, told
//! apart by their first bytes, with the schema metadata they were written with (for
//! `merge`, `--resume` and the readers of columns: `sweep::SweepFile`, `columns::Table`).
//!
//! A damaged file is refused with an error naming it, never a panic or an abort: its sizes
//! are checked against the file's length before it is decoded (`check`), and a panic of the
//! decoders on what no check sees becomes an error (`guard`).

mod check;
mod guard;

use super::format::{BATCH_ROWS, Format};
use crate::reference::Outcome;
use anyhow::{anyhow, bail};
use arrow_array::RecordBatch;
use arrow_schema::SchemaRef;
pub use check::{arrow_file, compressed_sizes, parquet_chunks};
pub use guard::{damaged, guarded};
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

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

/// The batches of a file, and its schema with the metadata it was written with. A damaged
/// file is refused, here or by the batch it spoils: "cannot read PATH: the file is damaged
/// (...)".
pub fn open(path: &Path, format: Format) -> anyhow::Result<(SchemaRef, Batches)> {
    let context = |e: &dyn std::fmt::Display| anyhow!("cannot read {}: {e}", path.display());
    let mut file = File::open(path).map_err(|e| context(&e))?;
    let len = file.metadata().map_err(|e| context(&e))?.len();
    let (schema, batches): (SchemaRef, Box<dyn Iterator<Item = _>>) = match format {
        Format::Arrow => {
            arrow_file(&mut file, len)
                .and_then(|()| compressed_sizes(&mut file, 8))
                .map_err(|why| damaged(path, &why))?;
            let r = guarded(path, || {
                arrow_ipc::reader::FileReader::try_new(BufReader::new(file), None)
                    .map_err(|e| context(&e))
            })?;
            (r.schema(), Box::new(r))
        }
        Format::Parquet => guarded(path, || {
            let b = ParquetRecordBatchReaderBuilder::try_new(file).map_err(|e| context(&e))?;
            parquet_chunks(b.metadata(), len).map_err(|why| damaged(path, &why))?;
            // The reader's own batches carry no schema metadata: take the builder's schema.
            let schema = b.schema().clone();
            let r = b
                .with_batch_size(BATCH_ROWS)
                .build()
                .map_err(|e| context(&e))?;
            Ok((schema, Box::new(r) as Box<dyn Iterator<Item = _>>))
        })?,
    };
    let batches = Guarded {
        path: path.to_path_buf(),
        inner: Some(batches),
    };
    Ok((schema, Box::new(batches)))
}

/// The outcome named `name` in the outcome column of the file at `path`.
pub fn outcome_of(name: &str, path: &Path) -> anyhow::Result<Outcome> {
    Outcome::from_name(name).ok_or_else(|| anyhow!("{}: unknown outcome {name:?}", path.display()))
}

/// Record batches as a reader yields them; an error names the file.
pub type Batches = Box<dyn Iterator<Item = anyhow::Result<RecordBatch>>>;

/// The batches of a decoder, each decoded under the guard; the decoder is dropped after
/// an error, so that a damaged file ends its batches.
struct Guarded {
    path: PathBuf,
    inner: Option<Box<dyn Iterator<Item = Result<RecordBatch, arrow_schema::ArrowError>>>>,
}

impl Iterator for Guarded {
    type Item = anyhow::Result<RecordBatch>;

    fn next(&mut self) -> Option<Self::Item> {
        let inner = self.inner.as_mut()?;
        let next = match guard::catch(|| inner.next()) {
            Ok(next) => {
                next.map(|b| b.map_err(|e| anyhow!("cannot read {}: {e}", self.path.display())))
            }
            Err(why) => Some(Err(damaged(&self.path, &why))),
        };
        if !matches!(next, Some(Ok(_))) {
            self.inner = None;
        }
        next
    }
}
