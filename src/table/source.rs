//! The table's file as it streams: its head (kind and columns), then its rows in chunks,
//! from any row on. CSV gives records, Arrow IPC (file or stream) and Parquet record
//! batches; the kind is told by the first bytes. Each format is decoded in functions of
//! its own (`open_parquet`, `open_ipc_file`, `open_ipc_stream`, `csv_head`, and
//! `Rows::next_chunk`), which nothing else calls.

use super::cells::csv_reader;
use crate::output::read::{arrow_file, compressed_sizes, damaged, guarded, parquet_chunks};
use anyhow::{anyhow, bail};
use arrow_array::RecordBatch;
use arrow_schema::FieldRef;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

/// Rows per chunk of a CSV file (an Arrow or Parquet chunk is one of its record batches,
/// Parquet's cut to this many rows).
pub(super) const CHUNK_ROWS: usize = 8192;

/// Bytes of CSV text per chunk, at most (after the record that passes them): rows of long
/// text come a few at a time.
const CHUNK_BYTES: usize = 16 << 20;

/// The kind of a table's file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Kind {
    Csv,
    Parquet,
    ArrowFile,
    ArrowStream,
}

impl Kind {
    /// `csv`, `arrow` or `parquet`, as the sweep's metadata says.
    pub(super) fn format(self) -> &'static str {
        match self {
            Kind::Csv => "csv",
            Kind::Parquet => "parquet",
            Kind::ArrowFile | Kind::ArrowStream => "arrow",
        }
    }
}

/// The head of a table's file: its kind, its columns, and where its row groups start.
pub(super) struct Head {
    pub(super) kind: Kind,
    /// The columns' names, in the file's order.
    pub(super) names: Vec<String>,
    /// The columns' fields (Arrow and Parquet; none in CSV).
    pub(super) fields: Vec<FieldRef>,
    /// The first row of each Parquet row group, and the rows after the last.
    pub(super) row_groups: Vec<u64>,
}

/// Where a reader can start other than at the top: found as the file is first read.
#[derive(Debug, Clone, Default)]
pub(super) struct Marks {
    /// CSV: where row `i * every` starts.
    pub(super) csv: Vec<csv::Position>,
    /// Arrow IPC file: the first row of each record batch.
    pub(super) batches: Vec<u64>,
}

/// A message for an error of a decoder, naming the file and a codec it lacks.
pub(super) fn decode_error(path: &Path, e: &dyn std::fmt::Display) -> anyhow::Error {
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
}

fn open(path: &Path) -> anyhow::Result<File> {
    File::open(path).map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))
}

/// Reads the head of the table at `path`: Parquet (`PAR1`), an Arrow IPC file (`ARROW1`)
/// or stream (a continuation marker), else CSV (its header row).
pub(super) fn head(path: &Path) -> anyhow::Result<Head> {
    let mut first = Vec::with_capacity(64 * 1024);
    open(path)?
        .take(64 * 1024)
        .read_to_end(&mut first)
        .map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))?;
    let kind = if first.starts_with(b"PAR1") {
        Kind::Parquet
    } else if first.starts_with(b"ARROW1") {
        Kind::ArrowFile
    } else if first.starts_with(&[0xff, 0xff, 0xff, 0xff]) {
        Kind::ArrowStream
    } else {
        return csv_head(path, &first);
    };
    // Sizes that a decoder would trust (and allocate by) checked first, then decoded under
    // the guard: a damaged file is refused naming it, never a panic or an abort.
    let mut file = open(path)?;
    let len = file
        .metadata()
        .map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))?
        .len();
    let checked = match kind {
        Kind::ArrowFile => arrow_file(&mut file, len).and_then(|()| compressed_sizes(&mut file, 8)),
        Kind::ArrowStream => compressed_sizes(&mut file, 0),
        _ => Ok(()),
    };
    checked.map_err(|why| damaged(path, &why))?;
    let (fields, row_groups): (Vec<FieldRef>, Vec<u64>) = match kind {
        Kind::Parquet => guarded(path, || {
            let b = parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder::try_new(file)
                .map_err(|e| decode_error(path, &e))?;
            parquet_chunks(b.metadata(), len).map_err(|why| damaged(path, &why))?;
            let mut starts = vec![0u64];
            for g in b.metadata().row_groups() {
                let rows = u64::try_from(g.num_rows()).unwrap_or(0);
                starts.push(starts.last().copied().unwrap_or(0) + rows);
            }
            Ok((b.schema().fields().iter().cloned().collect(), starts))
        })?,
        Kind::ArrowFile => {
            let r = open_ipc_file(path, None)?;
            (r.schema().fields().iter().cloned().collect(), Vec::new())
        }
        _ => {
            let r = open_ipc_stream(path, None)?;
            (r.schema().fields().iter().cloned().collect(), Vec::new())
        }
    };
    Ok(Head {
        kind,
        names: fields.iter().map(|f| f.name().clone()).collect(),
        fields,
        row_groups,
    })
}

/// The head of a CSV file from its first bytes `first`: refused if its first line is not
/// text (the rest of the text is checked as the file streams, after the header's names).
fn csv_head(path: &Path, first: &[u8]) -> anyhow::Result<Head> {
    let line = first
        .iter()
        .position(|&b| b == b'\n')
        .map_or(first, |end| &first[..end]);
    if let Err(e) = std::str::from_utf8(line)
        && (e.error_len().is_some() || line.len() < first.len())
    {
        bail!(
            "{} is neither Parquet, Arrow nor CSV text (not UTF-8 at byte {})",
            path.display(),
            e.valid_up_to()
        );
    }
    let header: Vec<String> = csv_reader(open(path)?)
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
    Ok(Head {
        kind: Kind::Csv,
        names: header,
        fields: Vec::new(),
        row_groups: Vec::new(),
    })
}

type IpcFile = arrow_ipc::reader::FileReader<BufReader<File>>;
type IpcStream = arrow_ipc::reader::StreamReader<BufReader<File>>;
type ParquetRows = parquet::arrow::arrow_reader::ParquetRecordBatchReader;

fn open_ipc_file(path: &Path, projection: Option<Vec<usize>>) -> anyhow::Result<IpcFile> {
    let file = open(path)?;
    guarded(path, || {
        arrow_ipc::reader::FileReader::try_new_buffered(file, projection)
            .map_err(|e| decode_error(path, &e))
    })
}

fn open_ipc_stream(path: &Path, projection: Option<Vec<usize>>) -> anyhow::Result<IpcStream> {
    let file = open(path)?;
    guarded(path, || {
        arrow_ipc::reader::StreamReader::try_new_buffered(file, projection)
            .map_err(|e| decode_error(path, &e))
    })
}

/// The Parquet file's rows from `from` (in row group `group`, which starts at row
/// `group_start`), columns `projection`.
fn open_parquet(
    path: &Path,
    projection: Option<&[usize]>,
    group: usize,
    skip: u64,
) -> anyhow::Result<ParquetRows> {
    let file = open(path)?;
    guarded(path, || parquet_rows(path, file, projection, group, skip))
}

/// `open_parquet` of the opened `file`.
fn parquet_rows(
    path: &Path,
    file: File,
    projection: Option<&[usize]>,
    group: usize,
    skip: u64,
) -> anyhow::Result<ParquetRows> {
    use parquet::arrow::ProjectionMask;
    use parquet::arrow::arrow_reader::{RowSelection, RowSelector};
    let mut b = parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder::try_new(file)
        .map_err(|e| decode_error(path, &e))?
        .with_batch_size(CHUNK_ROWS);
    let groups = b.metadata().num_row_groups();
    if let Some(p) = projection {
        let mask = ProjectionMask::roots(b.parquet_schema(), p.iter().copied());
        b = b.with_projection(mask);
    }
    if group > 0 || skip > 0 {
        let rest: i64 = b.metadata().row_groups()[group..]
            .iter()
            .map(parquet::file::metadata::RowGroupMetaData::num_rows)
            .sum();
        let skip = usize::try_from(skip).unwrap_or(usize::MAX);
        b = b
            .with_row_groups((group..groups).collect())
            .with_row_selection(RowSelection::from(vec![
                RowSelector::skip(skip),
                RowSelector::select(usize::try_from(rest).unwrap_or(0).saturating_sub(skip)),
            ]));
    }
    b.build().map_err(|e| decode_error(path, &e))
}

/// A chunk of rows.
pub(super) enum Chunk {
    /// CSV records, each with its line.
    Csv(Vec<(csv::StringRecord, u64)>),
    /// Arrow or Parquet columns, in the order read (the projection's).
    Batch(RecordBatch),
}

impl Chunk {
    pub(super) fn rows(&self) -> usize {
        match self {
            Chunk::Csv(r) => r.len(),
            Chunk::Batch(b) => b.num_rows(),
        }
    }
}

enum Reader {
    Csv(csv::Reader<File>),
    Parquet(ParquetRows),
    ArrowFile(IpcFile),
    ArrowStream(IpcStream),
}

/// A reader of the table's rows in chunks, at row `at`.
pub(super) struct Rows {
    reader: Reader,
    /// The row the next chunk starts at.
    pub(super) at: u64,
    /// The rest of a record batch that a start inside it cut.
    pending: Option<RecordBatch>,
}

impl Rows {
    /// The rows of the table at `path` from row `from` on, columns `projection` (all if
    /// `None`; CSV records always have every field), starting where `marks` allow and
    /// reading on to `from`.
    pub(super) fn open(
        path: &Path,
        head: &Head,
        marks: &Marks,
        every: u64,
        from: u64,
        projection: Option<&[usize]>,
    ) -> anyhow::Result<Rows> {
        let mut rows = match head.kind {
            Kind::Csv => {
                let mut r = csv_reader(open(path)?);
                r.headers()
                    .map_err(|e| anyhow!("{}: {e}", path.display()))?;
                let mark = usize::try_from(from / every.max(1)).unwrap_or(usize::MAX);
                let mut at = 0;
                if let Some(pos) = marks.csv.get(mark).filter(|_| from > 0) {
                    r.seek(pos.clone())
                        .map_err(|e| anyhow!("{}: {e}", path.display()))?;
                    at = mark as u64 * every;
                }
                Rows {
                    reader: Reader::Csv(r),
                    at,
                    pending: None,
                }
            }
            Kind::Parquet => {
                let group = head
                    .row_groups
                    .partition_point(|&s| s <= from)
                    .saturating_sub(1);
                let start = head.row_groups.get(group).copied().unwrap_or(0);
                let r = open_parquet(path, projection, group, from - start)?;
                return Ok(Rows {
                    reader: Reader::Parquet(r),
                    at: from,
                    pending: None,
                });
            }
            Kind::ArrowFile => {
                let mut r = open_ipc_file(path, projection.map(<[usize]>::to_vec))?;
                let batch = marks
                    .batches
                    .partition_point(|&s| s <= from)
                    .saturating_sub(1);
                let mut at = 0;
                if batch > 0 && batch < r.num_batches() {
                    r.set_index(batch).map_err(|e| decode_error(path, &e))?;
                    at = marks.batches[batch];
                }
                Rows {
                    reader: Reader::ArrowFile(r),
                    at,
                    pending: None,
                }
            }
            Kind::ArrowStream => Rows {
                reader: Reader::ArrowStream(open_ipc_stream(
                    path,
                    projection.map(<[usize]>::to_vec),
                )?),
                at: 0,
                pending: None,
            },
        };
        rows.skip_to(from, path)?;
        Ok(rows)
    }

    /// Reads on to row `to`.
    fn skip_to(&mut self, to: u64, path: &Path) -> anyhow::Result<()> {
        while self.at < to {
            if let Reader::Csv(r) = &mut self.reader {
                let mut record = csv::ByteRecord::new();
                if !r
                    .read_byte_record(&mut record)
                    .map_err(|e| anyhow!("{}: {e}", path.display()))?
                {
                    break;
                }
                self.at += 1;
                continue;
            }
            let left = usize::try_from(to - self.at).unwrap_or(usize::MAX);
            let Some(batch) = self.next_batch(path)? else {
                break;
            };
            if batch.num_rows() > left {
                self.pending = Some(batch.slice(left, batch.num_rows() - left));
                self.at = to;
            } else {
                self.at += batch.num_rows() as u64;
            }
        }
        Ok(())
    }
}

impl Rows {
    /// The next record batch of an Arrow or Parquet file.
    fn next_batch(&mut self, path: &Path) -> anyhow::Result<Option<RecordBatch>> {
        if let Some(b) = self.pending.take() {
            return Ok(Some(b));
        }
        // Decoded under the guard: a damaged batch is refused naming the file.
        guarded(path, || {
            let next = match &mut self.reader {
                Reader::Csv(_) => return Ok(None),
                Reader::Parquet(r) => r.next().map(|b| b.map_err(|e| decode_error(path, &e))),
                Reader::ArrowFile(r) => r.next().map(|b| b.map_err(|e| decode_error(path, &e))),
                Reader::ArrowStream(r) => r.next().map(|b| b.map_err(|e| decode_error(path, &e))),
            };
            next.transpose()
        })
    }

    /// The next chunk of rows, at most `max` of them, or `None` at the end of the table: up
    /// to `CHUNK_ROWS` CSV records, or the next record batch (the rest of it kept for the
    /// next chunk).
    pub(super) fn next_chunk(&mut self, path: &Path, max: usize) -> anyhow::Result<Option<Chunk>> {
        let chunk = if let Reader::Csv(r) = &mut self.reader {
            let mut records = Vec::new();
            let mut record = csv::StringRecord::new();
            let mut bytes = 0;
            while records.len() < CHUNK_ROWS.min(max)
                && bytes < CHUNK_BYTES
                && r.read_record(&mut record)
                    .map_err(|e| super::cells::csv_error(&e, path))?
            {
                let line = record.position().map_or(0, csv::Position::line);
                bytes += record.as_slice().len();
                records.push((record.clone(), line));
            }
            (!records.is_empty()).then_some(Chunk::Csv(records))
        } else {
            match self.next_batch(path)? {
                Some(b) if b.num_rows() > max => {
                    self.pending = Some(b.slice(max, b.num_rows() - max));
                    Some(Chunk::Batch(b.slice(0, max)))
                }
                b => b.map(Chunk::Batch),
            }
        };
        if let Some(c) = &chunk {
            self.at += c.rows() as u64;
        }
        Ok(chunk)
    }
}
