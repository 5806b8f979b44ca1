//! The sweep file written as rows come, in batches of a fixed row count, under its name
//! only when finished; the batches made (and, for Parquet, encoded) on any thread by a
//! `BatchMaker`; and a rebatcher for files made of other files (merge, resume).

use super::batch::{batch, recoded};
use super::schema::{SweepInfo, schema};
use crate::output::format::{BATCH_ROWS, Format, parquet_properties};
use crate::output::{AtomicFile, IpcWriter, Out};
use crate::sweep::Row;
use arrow_array::{Array, ArrayRef, Float64Array, RecordBatch, UInt32Array};
use arrow_schema::SchemaRef;
use arrow_select::concat::concat_batches;
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_writer::{ArrowColumnChunk, ArrowRowGroupWriterFactory, compute_leaves};
use parquet::file::writer::SerializedFileWriter;
use std::path::Path;
use std::sync::Arc;

/// The writer of the file's format. Parquet's row groups are encoded by the `BatchMaker`
/// that made them (on the thread that made them), or here for batches written whole, as
/// `ArrowWriter` encodes them: the same bytes.
enum Writer {
    Arrow(IpcWriter),
    Parquet {
        file: SerializedFileWriter<Out>,
        row_groups: Arc<ArrowRowGroupWriterFactory>,
    },
}

/// Makes the record batch of a stretch of rows (and, for a Parquet file, encodes it as a
/// row group): the work of the writer that any thread can do, for `SweepWriter::push_made`.
#[derive(Clone)]
pub struct BatchMaker {
    schema: SchemaRef,
    legs: usize,
    table: Option<Arc<crate::scenario::InputTable>>,
    row_groups: Option<Arc<ArrowRowGroupWriterFactory>>,
}

/// A batch made by a `BatchMaker`: its rows, and for Parquet their column chunks.
pub struct Made {
    batch: RecordBatch,
    chunks: Option<Vec<ArrowColumnChunk>>,
}

impl BatchMaker {
    /// The batch of `rows` (consecutive samples, in order).
    pub fn make(&self, rows: &[Row]) -> anyhow::Result<Made> {
        let kept = match (&self.table, rows.first()) {
            (Some(t), Some(r)) => t.kept_rows(r.sample.index, rows.len())?,
            _ => Vec::new(),
        };
        let batch = batch(&self.schema, self.legs, rows, kept)?;
        let chunks = match &self.row_groups {
            Some(f) => Some(row_group(f, &self.schema, &batch)?),
            None => None,
        };
        Ok(Made { batch, chunks })
    }
}

/// The column chunks of `b` as one Parquet row group, as `ArrowWriter` encodes them.
fn row_group(
    factory: &ArrowRowGroupWriterFactory,
    schema: &SchemaRef,
    b: &RecordBatch,
) -> anyhow::Result<Vec<ArrowColumnChunk>> {
    // The row group's number matters only to encryption, which these files do not use.
    let mut writers = factory.create_column_writers(0)?;
    let mut leaves = writers.iter_mut();
    for (field, column) in schema.fields().iter().zip(b.columns()) {
        for leaf in compute_leaves(field.as_ref(), column)? {
            leaves
                .next()
                .expect("a writer for every leaf column")
                .write(&leaf)?;
        }
    }
    Ok(writers
        .into_iter()
        .map(|w| w.close())
        .collect::<Result<_, _>>()?)
}

/// The file a sweep writer writes, under its name only when finished.
struct FileOut {
    path: std::path::PathBuf,
    file: AtomicFile,
    sink: Writer,
}

/// Writes the batches its `maker` makes of the rows as they come (`push_made`), of
/// `BATCH_ROWS` rows, to a file that appears under its name only after `finish`; or keeps
/// them in memory (`in_memory`, `keeping`), or both. A resumed sweep's first batch may
/// begin with rows it took over (`hold`).
pub struct SweepWriter {
    out: Option<FileOut>,
    schema: SchemaRef,
    legs: usize,
    /// The first rows of the next batch, which came as a record batch (`hold`: those a
    /// resumed sweep took over after its whole batches).
    held: Option<RecordBatch>,
    rows: u64,
    /// The table of inputs whose columns pass through (`--keep-columns`).
    table: Option<Arc<crate::scenario::InputTable>>,
    /// The batches written so far, where they are kept (`keeping`).
    kept: Option<Vec<RecordBatch>>,
}

impl SweepWriter {
    /// Opens the temporary file for `path`.
    pub fn create(
        path: &Path,
        format: Format,
        legs: usize,
        info: &SweepInfo<'_>,
    ) -> anyhow::Result<SweepWriter> {
        let mut writer = SweepWriter::in_memory(legs, info);
        let (file, out) = AtomicFile::create(path)?;
        let sink = match format {
            Format::Arrow => Writer::Arrow(IpcWriter::new(&file, out, &writer.schema)?),
            Format::Parquet => {
                let props = parquet_properties(&writer.schema, Some(BATCH_ROWS));
                let (file, row_groups) =
                    ArrowWriter::try_new(out, writer.schema.clone(), Some(props))?
                        .into_serialized_writer()?;
                Writer::Parquet {
                    file,
                    row_groups: Arc::new(row_groups),
                }
            }
        };
        writer.out = Some(FileOut {
            path: path.to_path_buf(),
            file,
            sink,
        });
        writer.kept = None;
        Ok(writer)
    }

    /// A writer of no file that keeps its batches (`finish_kept`): a sweep held in memory.
    #[must_use]
    pub fn in_memory(legs: usize, info: &SweepInfo<'_>) -> SweepWriter {
        SweepWriter {
            out: None,
            schema: schema(legs, info),
            legs,
            held: None,
            rows: 0,
            table: None,
            kept: Some(Vec::new()),
        }
    }

    /// Keeps the batches it writes as well (`finish_kept`).
    #[must_use]
    pub fn keeping(mut self) -> SweepWriter {
        self.kept.get_or_insert_with(Vec::new);
        self
    }

    /// Passes the kept columns of `table` (`SweepInfo::kept`) through, row by row.
    #[must_use]
    pub fn with_table(mut self, table: Option<Arc<crate::scenario::InputTable>>) -> SweepWriter {
        self.table = table;
        self
    }

    /// What makes this writer's batches on other threads (`push_made`).
    #[must_use]
    pub fn maker(&self) -> BatchMaker {
        BatchMaker {
            schema: self.schema.clone(),
            legs: self.legs,
            table: self.table.clone(),
            row_groups: self.row_groups(),
        }
    }

    /// The encoder of a Parquet file's row groups (none for Arrow or no file).
    fn row_groups(&self) -> Option<Arc<ArrowRowGroupWriterFactory>> {
        match &self.out {
            Some(FileOut {
                sink: Writer::Parquet { row_groups, .. },
                ..
            }) => Some(row_groups.clone()),
            _ => None,
        }
    }

    /// The rows the next batch takes before it is full (fewer than `BATCH_ROWS` where it
    /// begins with rows a resumed sweep took over).
    #[must_use]
    pub fn room(&self) -> usize {
        BATCH_ROWS - self.held.as_ref().map_or(0, RecordBatch::num_rows)
    }

    /// Writes a batch its `maker` made of the next rows: the next batch's `room` rows, or
    /// fewer as the last.
    pub fn push_made(&mut self, made: Made) -> anyhow::Result<()> {
        match self.held.take() {
            // The rows a resumed sweep took over come first: the batch is encoded here.
            Some(h) => {
                let whole = concat_batches(&self.schema, [&h, &made.batch])?;
                self.write_batch(&zero_nulls(&whole)?)
            }
            None => self.write_made(made),
        }
    }

    /// Takes `rows` (fewer than a batch, in this writer's schema) as the first rows of the
    /// next batch, which the batch made after them fills: a resumed sweep's rows after the
    /// whole batches it took over, so that its file is cut into the batches of a sweep that
    /// never stopped.
    pub fn hold(&mut self, rows: RecordBatch) {
        debug_assert!(
            self.held.is_none() && rows.num_rows() < BATCH_ROWS,
            "hold once, less than a batch"
        );
        if rows.num_rows() > 0 {
            self.held = Some(rows);
        }
    }

    /// Writes the held rows, if no batch came to fill them.
    fn flush(&mut self) -> anyhow::Result<()> {
        match self.held.take() {
            Some(b) => self.write_batch(&zero_nulls(&b)?),
            None => Ok(()),
        }
    }

    /// The schema every batch is written in.
    #[must_use]
    pub fn schema(&self) -> &SchemaRef {
        &self.schema
    }

    /// Writes a whole batch as it is (for `merge`, which cuts its batches itself), its coded
    /// columns coded as this writer's own batches (`batch::recoded`): joining batches
    /// (`concat_batches`) joins their dictionaries, which an Arrow IPC file refuses after its
    /// first batch.
    pub fn write_batch(&mut self, b: &RecordBatch) -> anyhow::Result<()> {
        let b = &recoded(b, &self.schema)?;
        let Some(row_groups) = self.row_groups() else {
            return self.write_made(Made {
                batch: b.clone(),
                chunks: None,
            });
        };
        // Parquet: in row groups of at most `BATCH_ROWS`, as `ArrowWriter` cuts a batch.
        let mut at = 0;
        loop {
            let part = b.slice(at, (b.num_rows() - at).min(BATCH_ROWS));
            at += part.num_rows();
            let chunks = Some(row_group(&row_groups, &self.schema, &part)?);
            self.write_made(Made {
                batch: part,
                chunks,
            })?;
            if at == b.num_rows() {
                return Ok(());
            }
        }
    }

    /// Writes a made batch: an Arrow batch encoded here, or a Parquet row group of the
    /// column chunks encoded where it was made.
    fn write_made(&mut self, made: Made) -> anyhow::Result<()> {
        let Made { batch: b, chunks } = made;
        if b.num_rows() == 0 {
            return Ok(());
        }
        if let Some(out) = &mut self.out {
            let written = match (&mut out.sink, chunks) {
                (Writer::Arrow(w), _) => w.write(&b).map_err(anyhow::Error::from),
                (Writer::Parquet { file, .. }, Some(chunks)) => append_row_group(file, chunks),
                (Writer::Parquet { .. }, None) => {
                    anyhow::bail!("a Parquet batch made without its column chunks")
                }
            };
            written.map_err(|e| crate::output::cannot_write(out.file.partial_path(), e))?;
        }
        self.rows += b.num_rows() as u64;
        if let Some(kept) = &mut self.kept {
            kept.push(b);
        }
        Ok(())
    }

    /// Writes the last batch, closes the file and gives it its name; removes the file of an
    /// interrupted sweep to the same path (`OUT.interrupted`), which this one continued or
    /// makes obsolete. Returns the row count.
    pub fn finish(self) -> anyhow::Result<u64> {
        Ok(self.finish_kept()?.0)
    }

    /// As `finish`, and returns the batches kept (`in_memory`, `keeping`; none otherwise).
    pub fn finish_kept(self) -> anyhow::Result<(u64, Vec<RecordBatch>)> {
        let (rows, _, kept) = self.close(None)?;
        Ok((rows, kept))
    }

    /// Writes the rows pushed so far and closes the file as a valid one, under the name of
    /// an interrupted sweep (`OUT.interrupted`), not the final name. Returns the row count
    /// and that path; `None` where the output is not a regular file (a device, a FIFO,
    /// standard output): the rows went there, and nothing is made beside it; and none for
    /// a writer of no file, whose batches are let go.
    pub fn finish_interrupted(self) -> anyhow::Result<(u64, Option<std::path::PathBuf>)> {
        let Some(path) = self
            .out
            .as_ref()
            .map(|o| crate::output::interrupted_path(&o.path))
        else {
            return Ok((self.rows, None));
        };
        let (rows, made, _) = self.close(Some(&path))?;
        Ok((rows, made.then_some(path)))
    }

    /// Writes the last rows and closes the file, renamed onto `name` instead of its final
    /// path if given. Returns the row count, whether `name` was made, and the batches kept.
    fn close(mut self, name: Option<&Path>) -> anyhow::Result<(u64, bool, Vec<RecordBatch>)> {
        self.flush()?;
        let kept = self.kept.take().unwrap_or_default();
        let Some(FileOut { path, file, sink }) = self.out.take() else {
            return Ok((self.rows, false, kept));
        };
        let out = match sink {
            Writer::Arrow(w) => w.finish().map_err(anyhow::Error::from),
            Writer::Parquet { file, .. } => file.into_inner().map_err(anyhow::Error::from),
        };
        let failed = |e| crate::output::cannot_write(file.partial_path(), e);
        let mut out = out.map_err(failed)?;
        std::io::Write::flush(&mut out).map_err(|e| failed(e.into()))?;
        let made = match name {
            None => {
                // A finished sweep makes an interrupted one to the same path obsolete.
                let stale = crate::output::interrupted_path(&path);
                file.commit_replacing(out, Some(&stale))?;
                false
            }
            Some(name) => file.commit_as(out, name)?,
        };
        Ok((self.rows, made, kept))
    }
}

/// Appends `chunks` to `file` as its next row group.
fn append_row_group(
    file: &mut SerializedFileWriter<Out>,
    chunks: Vec<ArrowColumnChunk>,
) -> anyhow::Result<()> {
    let mut group = file.next_row_group()?;
    for chunk in chunks {
        chunk.append_to_row_group(&mut group)?;
    }
    group.close()?;
    Ok(())
}

/// Cuts a stream of batches into batches of `BATCH_ROWS` rows (the last one shorter), as
/// the sweep writes them, holding at most one batch's rows.
pub struct Rebatcher {
    schema: SchemaRef,
    pieces: Vec<RecordBatch>,
    rows: usize,
}

impl Rebatcher {
    /// An empty rebatcher of batches with `schema`.
    #[must_use]
    pub fn new(schema: SchemaRef) -> Rebatcher {
        Rebatcher {
            schema,
            pieces: Vec::new(),
            rows: 0,
        }
    }

    /// Takes the rows of `b` (columns as in the schema), writing every full batch.
    pub fn push(&mut self, b: RecordBatch, writer: &mut SweepWriter) -> anyhow::Result<()> {
        // The same columns, under the schema of the whole sweep (no shard metadata), coded
        // as the sweep codes them.
        let mut b = recoded(&b, &self.schema)?;
        while self.rows + b.num_rows() >= BATCH_ROWS {
            let take = BATCH_ROWS - self.rows;
            self.pieces.push(b.slice(0, take));
            b = b.slice(take, b.num_rows() - take);
            self.rows = 0;
            self.write(writer)?;
        }
        if b.num_rows() > 0 {
            self.rows += b.num_rows();
            self.pieces.push(b);
        }
        Ok(())
    }

    /// Writes the rows left, if any.
    pub fn finish(mut self, writer: &mut SweepWriter) -> anyhow::Result<()> {
        if self.pieces.is_empty() {
            return Ok(());
        }
        self.write(writer)
    }

    /// Hands the rows left, fewer than a batch, to `writer` as the first rows of its next
    /// batch (`SweepWriter::hold`), rather than writing them as a shorter batch.
    pub fn hand_over(self, writer: &mut SweepWriter) -> anyhow::Result<()> {
        if !self.pieces.is_empty() {
            writer.hold(concat_batches(&self.schema, &self.pieces)?);
        }
        Ok(())
    }

    /// Writes the pieces as one batch of fresh (unsliced) arrays.
    fn write(&mut self, writer: &mut SweepWriter) -> anyhow::Result<()> {
        let whole = zero_nulls(&concat_batches(&self.schema, &self.pieces)?)?;
        self.pieces.clear();
        writer.write_batch(&whole)
    }
}

/// `b` with 0 under the nulls of its Float64 and UInt32 columns (the touchdown state's
/// first leg), as a sweep writes them: a Parquet
/// reader leaves there what its decoder left, which no reader shows but the bytes of a
/// file merged from Parquet shards would.
fn zero_nulls(b: &RecordBatch) -> anyhow::Result<RecordBatch> {
    let columns = b
        .columns()
        .iter()
        .map(|c| {
            if c.null_count() == 0 {
                return c.clone();
            }
            if let Some(a) = c.as_any().downcast_ref::<Float64Array>() {
                return Arc::new(a.iter().collect::<Float64Array>()) as ArrayRef;
            }
            match c.as_any().downcast_ref::<UInt32Array>() {
                Some(a) => Arc::new(a.iter().collect::<UInt32Array>()),
                None => c.clone(),
            }
        })
        .collect();
    Ok(RecordBatch::try_new(b.schema(), columns)?)
}
