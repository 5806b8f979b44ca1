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
use arrow_array::cast::AsArray;
use arrow_array::{Array, RecordBatch, StringArray};
use arrow_schema::{DataType, SchemaRef};
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

/// A text column of a file, as written: plain (`Utf8`, as sweeps before the coded outcome
/// wrote `outcome` and `limits_broken`) or coded into a dictionary of its texts.
pub struct Texts<'a> {
    names: &'a StringArray,
    /// For a coded column: the column (for its nulls) and each row's index into `names`.
    coded: Option<(&'a dyn Array, Vec<usize>)>,
}

impl<'a> Texts<'a> {
    /// The texts of `array`, if it is a column of text (plain or coded); `None` otherwise.
    #[must_use]
    pub fn of(array: &'a dyn Array) -> Option<Texts<'a>> {
        match array.data_type() {
            DataType::Utf8 => Some(Texts {
                names: array.as_string::<i32>(),
                coded: None,
            }),
            DataType::Dictionary(_, value) if **value == DataType::Utf8 => {
                let d = array.as_any_dictionary_opt()?;
                Some(Texts {
                    names: d.values().as_string::<i32>(),
                    coded: Some((array, d.normalized_keys())),
                })
            }
            _ => None,
        }
    }

    /// Rows.
    #[must_use]
    pub fn len(&self) -> usize {
        match &self.coded {
            Some((_, keys)) => keys.len(),
            None => self.names.len(),
        }
    }

    /// Whether it has no rows.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The text of row `i` (`None` where it is null).
    #[must_use]
    pub fn get(&self, i: usize) -> Option<&'a str> {
        let at = match &self.coded {
            Some((array, _)) if array.is_null(i) => return None,
            Some((_, keys)) => keys[i],
            None => i,
        };
        (!self.names.is_null(at)).then(|| self.names.value(at))
    }

    /// The text of each row, in order (`None` where it is null).
    pub fn iter(&self) -> impl Iterator<Item = Option<&'a str>> + '_ {
        (0..self.len()).map(|i| self.get(i))
    }
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
