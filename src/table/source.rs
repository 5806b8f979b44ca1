//! The table as read from its file: CSV (its records read as they are checked) or Arrow
//! IPC and Parquet (its columns), told apart by the first bytes; every cell to its sink.

use super::cells::{CellError, arrow_cells, csv_array, csv_cell, csv_error, csv_reader};
use super::sink::Sink;
use crate::output::read::{arrow_file, compressed_sizes, damaged, guarded};
use anyhow::{anyhow, bail};
use arrow_array::{Array, ArrayRef, RecordBatch};
use arrow_schema::{Field, FieldRef, Schema};
use std::path::Path;
use std::sync::Arc;

/// The table as read from its file.
pub(super) enum Source {
    /// Its header read; its records are read as they are checked (`fill`).
    Csv { header: Vec<String>, text: Vec<u8> },
    Arrow {
        format: &'static str,
        columns: Vec<(FieldRef, ArrayRef)>,
        rows: usize,
    },
}

impl Source {
    /// Tells the format from the first bytes: Parquet (`PAR1`), an Arrow IPC file
    /// (`ARROW1`) or stream (a continuation marker), else CSV.
    pub(super) fn parse(path: &Path, bytes: Vec<u8>) -> anyhow::Result<Source> {
        let context = |e: &dyn std::fmt::Display| {
            let text = e.to_string();
            match text.split("Disabled feature at compile time: ").nth(1) {
                Some(codec) => anyhow!(
                    "cannot read {}: it is compressed with {}, which touchdown does not read \
                     (Parquet: snappy, zstd, gzip, lz4 or none; Arrow: lz4, zstd or none)",
                    path.display(),
                    codec.trim()
                ),
                None => anyhow!("cannot read {}: {text}", path.display()),
            }
        };
        // Decoded under the guard (a damaged file is refused naming it, never a panic),
        // Arrow's sizes checked first (what the decoder allocates by).
        let batches: (Vec<RecordBatch>, Arc<Schema>, &'static str) = if bytes.starts_with(b"PAR1") {
            guarded(path, || {
                let b = parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder::try_new(
                    bytes::Bytes::from(bytes),
                )
                .map_err(|e| context(&e))?;
                let schema = b.schema().clone();
                let r = b.build().map_err(|e| context(&e))?;
                let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
                Ok((batches, schema, "parquet"))
            })?
        } else if bytes.starts_with(b"ARROW1") {
            arrow_file(&mut std::io::Cursor::new(&bytes), bytes.len() as u64)
                .and_then(|()| compressed_sizes(&bytes, 8))
                .map_err(|why| damaged(path, &why))?;
            guarded(path, || {
                let r = arrow_ipc::reader::FileReader::try_new(std::io::Cursor::new(bytes), None)
                    .map_err(|e| context(&e))?;
                let schema = r.schema();
                let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
                Ok((batches, schema, "arrow"))
            })?
        } else if bytes.starts_with(&[0xff, 0xff, 0xff, 0xff]) {
            compressed_sizes(&bytes, 0).map_err(|why| damaged(path, &why))?;
            guarded(path, || {
                let r = arrow_ipc::reader::StreamReader::try_new(std::io::Cursor::new(bytes), None)
                    .map_err(|e| context(&e))?;
                let schema = r.schema();
                let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
                Ok((batches, schema, "arrow"))
            })?
        } else {
            return Source::csv(path, bytes);
        };
        let (batches, schema, format) = batches;
        let rows = batches.iter().map(RecordBatch::num_rows).sum();
        let columns = schema
            .fields()
            .iter()
            .enumerate()
            .map(|(j, f)| {
                let pieces: Vec<&dyn Array> =
                    batches.iter().map(|b| b.column(j).as_ref()).collect();
                let whole = if pieces.is_empty() {
                    arrow_array::new_empty_array(f.data_type())
                } else {
                    arrow_select::concat::concat(&pieces).map_err(|e| context(&e))?
                };
                Ok((f.clone(), whole))
            })
            .collect::<anyhow::Result<_>>()?;
        Ok(Source::Arrow {
            format,
            columns,
            rows,
        })
    }

    fn csv(path: &Path, bytes: Vec<u8>) -> anyhow::Result<Source> {
        if let Err(e) = std::str::from_utf8(&bytes) {
            bail!(
                "{} is neither Parquet, Arrow nor CSV text (not UTF-8 at byte {})",
                path.display(),
                e.valid_up_to()
            );
        }
        let header: Vec<String> = csv_reader(&bytes)
            .headers()
            .map_err(|e| anyhow!("{}: {e}", path.display()))?
            .iter()
            .map(str::to_string)
            .collect();
        if header.iter().all(String::is_empty) {
            bail!("{}: no header row naming the columns", path.display());
        }
        if let Some(j) = header.iter().position(String::is_empty) {
            bail!(
                "{}: column {} has no name in the header",
                path.display(),
                j + 1
            );
        }
        // The CSV reader skips blank lines, which in a one-column table are empty values:
        // refuse one before the last row (outside a quoted field: after an even number of
        // quotes), as it would shift every later row's sample.
        let text = std::str::from_utf8(&bytes).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        let last = lines
            .iter()
            .rposition(|l| !l.trim().is_empty())
            .unwrap_or(0);
        let mut quotes = 0;
        for (i, l) in lines[..last].iter().enumerate() {
            if i > 0 && quotes % 2 == 0 && l.trim().is_empty() {
                bail!(
                    "{}: line {} is blank: every row needs its values (a blank line would \
                     shift every later row's sample)",
                    path.display(),
                    i + 1
                );
            }
            quotes += l.matches('"').count();
        }
        Ok(Source::Csv {
            header,
            text: bytes,
        })
    }

    pub(super) fn format(&self) -> &'static str {
        match self {
            Source::Csv { .. } => "csv",
            Source::Arrow { format, .. } => format,
        }
    }

    pub(super) fn names(&self) -> Vec<String> {
        match self {
            Source::Csv { header, .. } => header.clone(),
            Source::Arrow { columns, .. } => {
                columns.iter().map(|(f, _)| f.name().clone()).collect()
            }
        }
    }

    /// Feeds every cell to its column's sink; gives the number of rows, and the kept
    /// columns as one batch.
    pub(super) fn fill(
        &self,
        sinks: &mut [Sink],
        path: &Path,
    ) -> anyhow::Result<(usize, Option<RecordBatch>)> {
        let names = self.names();
        let mut kept: Vec<(FieldRef, ArrayRef)> = Vec::new();
        let rows = match self {
            Source::Csv { text, .. } => {
                let mut reader = csv_reader(text);
                let mut record = csv::StringRecord::new();
                let mut texts: Vec<Vec<String>> = vec![Vec::new(); sinks.len()];
                let mut row = 0;
                while reader
                    .read_record(&mut record)
                    .map_err(|e| csv_error(&e, path))?
                {
                    let line = record.position().map_or(0, csv::Position::line);
                    for (j, sink) in sinks.iter_mut().enumerate() {
                        if sink.is_kept() {
                            texts[j].push(record[j].to_string());
                            continue;
                        }
                        sink.take(row, csv_cell(&record[j])).map_err(|why| {
                            anyhow!(
                                "{}: row {row} (line {line}), column {}: {why}",
                                path.display(),
                                names[j]
                            )
                        })?;
                    }
                    row += 1;
                }
                for (j, sink) in sinks.iter().enumerate() {
                    if sink.is_kept() {
                        let array = csv_array(texts[j].iter().map(String::as_str));
                        let field = Field::new(&names[j], array.data_type().clone(), true);
                        kept.push((Arc::new(field), array));
                    }
                }
                row
            }
            Source::Arrow { columns, rows, .. } => {
                for ((field, array), sink) in columns.iter().zip(sinks.iter_mut()) {
                    if sink.is_kept() {
                        kept.push((field.clone(), array.clone()));
                        continue;
                    }
                    let fail = |row: usize, why: String| {
                        anyhow!(
                            "{}: row {row}, column {}: {why}",
                            path.display(),
                            field.name()
                        )
                    };
                    arrow_cells(array, &mut |row, cell| {
                        sink.take(row, cell).map_err(|why| fail(row, why))
                    })
                    .map_err(|e| match e {
                        CellError::Type(t) => anyhow!(
                            "{}: column {} is of type {t}: its values must be numbers",
                            path.display(),
                            field.name()
                        ),
                        CellError::At(e) => e,
                    })?;
                }
                *rows
            }
        };
        if kept.is_empty() {
            return Ok((rows, None));
        }
        let (fields, arrays): (Vec<FieldRef>, Vec<ArrayRef>) = kept.into_iter().unzip();
        let batch = RecordBatch::try_new(Arc::new(Schema::new(fields)), arrays)?;
        Ok((rows, Some(batch)))
    }
}
