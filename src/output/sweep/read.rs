//! The one reader of sweep files: a sweep (or shard) file of touchdown opened, its
//! metadata and leg count, and its batches with typed columns by name and the outcome of
//! each row, for every command that reads a sweep's columns (report, compare,
//! sensitivity, study, trace --sweep); and a sweep held in memory (`SweepSource::Memory`:
//! Python's), read as a file is.

use crate::output::read::{Batches, Texts, format_of, open, outcome_of};
use crate::reference::Outcome;
use anyhow::{anyhow, bail};
use arrow_array::{Array, Float64Array, RecordBatch, UInt32Array, UInt64Array};
use arrow_schema::SchemaRef;
use std::path::{Path, PathBuf};

/// A sweep (or shard) file, Arrow IPC or Parquet, opened: its schema with the metadata it
/// was written with, and its batches, read as they are asked for (`batches`).
pub struct SweepFile {
    path: PathBuf,
    schema: SchemaRef,
    batches: Batches,
}

/// Where the rows of a sweep come from: a sweep (or shard) file, or record batches held
/// in memory with the schema and metadata such a file has. Opened as often as a reader
/// needs (`open`, `batches`): each time from the first row.
pub enum SweepSource {
    /// A sweep (or shard) file, Arrow IPC or Parquet.
    Path(PathBuf),
    /// A sweep held in memory.
    Memory {
        /// What messages call it, where they name a file's path.
        name: String,
        /// Its schema, with the metadata of a sweep file (`touchdown.kind = sweep`, ...).
        schema: SchemaRef,
        /// Its rows, in sample order.
        batches: Vec<RecordBatch>,
    },
}

impl SweepSource {
    /// What messages call it: the file's path, or the name of the sweep in memory.
    #[must_use]
    pub fn name(&self) -> &Path {
        match self {
            SweepSource::Path(path) => path,
            SweepSource::Memory { name, .. } => Path::new(name),
        }
    }

    /// Its schema and batches, from the first row; anything but a sweep is refused, saying
    /// what it is.
    pub fn batches(&self) -> anyhow::Result<(SchemaRef, Batches)> {
        let (schema, batches) = match self {
            SweepSource::Path(path) => open(path, format_of(path)?)?,
            SweepSource::Memory {
                schema, batches, ..
            } => (
                schema.clone(),
                Box::new(batches.clone().into_iter().map(Ok)) as Batches,
            ),
        };
        let kind = schema.metadata().get("touchdown.kind").map(String::as_str);
        let name = self.name().display();
        match (kind, self) {
            (Some("sweep"), _) => Ok((schema, batches)),
            (Some(kind), SweepSource::Path(_)) => {
                bail!("{name} is not a sweep file of touchdown (it is a {kind} file)")
            }
            (None, SweepSource::Path(_)) => bail!("{name} is not a sweep file of touchdown"),
            (Some(kind), SweepSource::Memory { .. }) => bail!(
                "{name} is not a sweep of touchdown: its schema's metadata says touchdown.kind \
                 = {kind}"
            ),
            (None, SweepSource::Memory { .. }) => bail!(
                "{name} is not a sweep of touchdown: its schema has no metadata touchdown.kind \
                 = sweep (a table read from a sweep file has it, unless a conversion dropped \
                 the schema's metadata)"
            ),
        }
    }

    /// Opened as a `SweepFile`.
    pub fn open(&self) -> anyhow::Result<SweepFile> {
        let (schema, batches) = self.batches()?;
        Ok(SweepFile {
            path: self.name().to_path_buf(),
            schema,
            batches,
        })
    }
}

impl SweepFile {
    /// Opens the sweep (or shard) file at `path`; any other file is refused, saying what
    /// it is.
    pub fn open(path: &Path) -> anyhow::Result<SweepFile> {
        SweepSource::Path(path.to_path_buf()).open()
    }

    /// The path it was opened at (of a sweep held in memory: its name).
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Its schema, with the metadata.
    #[must_use]
    pub fn schema(&self) -> &SchemaRef {
        &self.schema
    }

    /// The schema metadata it was written with (`touchdown.seed`, `touchdown.scenario`, ...).
    #[must_use]
    pub fn metadata(&self) -> &arrow_schema::Metadata {
        self.schema.metadata()
    }

    /// The number of legs of its lander (its per-leg peak force columns).
    #[must_use]
    pub fn legs(&self) -> usize {
        leg_count(&self.schema)
    }

    /// Its batches in file order, each with its columns by name; an error of the file names
    /// it.
    pub fn batches(&mut self) -> impl Iterator<Item = anyhow::Result<SweepBatch<'_>>> + '_ {
        let path = self.path.as_path();
        self.batches
            .by_ref()
            .map(move |b| b.map(|batch| SweepBatch { batch, path }))
    }
}

/// A batch of rows of a sweep file, its columns typed by name; a column that is missing
/// or of another type is an error naming the file and the column.
pub struct SweepBatch<'a> {
    batch: RecordBatch,
    path: &'a Path,
}

impl SweepBatch<'_> {
    /// Its rows.
    #[must_use]
    pub fn rows(&self) -> usize {
        self.batch.num_rows()
    }

    /// Whether it has a column `name`.
    #[must_use]
    pub fn has(&self, name: &str) -> bool {
        self.batch.column_by_name(name).is_some()
    }

    /// The column `name`, if it is of type `A`; else the error `{path}: no {kind} column
    /// {name}`.
    fn typed<A: Array + 'static>(&self, name: &str, kind: &str) -> anyhow::Result<&A> {
        self.batch
            .column_by_name(name)
            .and_then(|c| c.as_any().downcast_ref::<A>())
            .ok_or_else(|| anyhow!("{}: no {kind} column {name}", self.path.display()))
    }

    /// A Float64 column, by name.
    pub fn f64s(&self, name: &str) -> anyhow::Result<&Float64Array> {
        self.typed(name, "Float64")
    }

    /// A UInt64 column (`sample`, `sample_seed`, `steps`), by name.
    pub fn u64s(&self, name: &str) -> anyhow::Result<&UInt64Array> {
        self.typed(name, "UInt64")
    }

    /// A UInt32 column (`terrain_tile`, `bounces`, `firings`), by name.
    pub fn u32s(&self, name: &str) -> anyhow::Result<&UInt32Array> {
        self.typed(name, "UInt32")
    }

    /// A text column (`limits_broken`), plain or coded, by name.
    pub fn strs(&self, name: &str) -> anyhow::Result<Texts<'_>> {
        self.batch
            .column_by_name(name)
            .and_then(|c| Texts::of(c.as_ref()))
            .ok_or_else(|| anyhow!("{}: no text column {name}", self.path.display()))
    }

    /// The Float64 columns `leg{k}_{what}` of legs 0 to `legs - 1`.
    pub fn per_leg(&self, legs: usize, what: &str) -> anyhow::Result<Vec<&Float64Array>> {
        (0..legs)
            .map(|k| self.f64s(&format!("leg{k}_{what}")))
            .collect()
    }

    /// The outcome of each row.
    pub fn outcomes(&self) -> anyhow::Result<Vec<Outcome>> {
        let names = self
            .batch
            .column_by_name("outcome")
            .and_then(|c| Texts::of(c.as_ref()))
            .ok_or_else(|| anyhow!("{}: no outcome column", self.path.display()))?;
        names
            .iter()
            .map(|name| outcome_of(name.unwrap_or(""), self.path))
            .collect()
    }
}

/// The samples a sweep file whose schema metadata `meta` gives asked for: its slice's for a
/// shard (`touchdown.sample_range`), else the sweep's (`touchdown.samples`); `None` where it
/// does not say.
#[must_use]
pub fn samples_asked<'a>(meta: impl Fn(&str) -> Option<&'a String>) -> Option<u64> {
    match meta(super::schema::SHARD_KEYS[1]) {
        Some(range) => {
            let (a, b) = range.split_once("..")?;
            b.parse::<u64>().ok()?.checked_sub(a.parse().ok()?)
        }
        None => meta("touchdown.samples")?.parse().ok(),
    }
}

/// What a reader says of the sweep file `name` that holds `rows` of the `asked` samples
/// (`samples_asked`) where it holds fewer: an interrupted sweep's rows, under the name it
/// was left at (`OUT.interrupted`) or renamed. `None` for a complete file.
#[must_use]
pub fn interrupted_note(name: &Path, rows: u64, asked: Option<u64>) -> Option<String> {
    let asked = asked.filter(|a| rows < *a)?;
    let file = name.file_name().unwrap_or_default().to_string_lossy();
    let resume = match file.strip_suffix(".interrupted") {
        Some(out) => format!(
            "`touchdown sweep --resume {}` finishes it",
            name.with_file_name(out).display()
        ),
        None => "`touchdown sweep --resume OUT` finishes it once it is named OUT.interrupted"
            .to_string(),
    };
    Some(format!(
        "{} of {} samples: an interrupted sweep; {resume}",
        grouped(rows),
        grouped(asked)
    ))
}

/// `n` with its digits in groups of three: `3,000`.
fn grouped(n: u64) -> String {
    let digits = n.to_string();
    let mut t = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            t.push(',');
        }
        t.push(d);
    }
    t
}

/// The number of legs of a sweep file with `schema` (its per-leg peak force columns).
#[must_use]
pub fn leg_count(schema: &arrow_schema::Schema) -> usize {
    schema
        .fields()
        .iter()
        .filter(|f| f.name().ends_with("_peak_normal_force_n"))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_short_of_its_samples_is_said_to_be_interrupted() {
        let note = interrupted_note(Path::new("d/s.arrow.interrupted"), 1113, Some(3000));
        assert_eq!(
            note.as_deref(),
            Some(
                "1,113 of 3,000 samples: an interrupted sweep; `touchdown sweep --resume \
                 d/s.arrow` finishes it"
            )
        );
        let renamed = interrupted_note(Path::new("part.arrow"), 999_999, Some(1_000_000));
        assert!(renamed.is_some_and(|n| n.starts_with("999,999 of 1,000,000 samples")));
        assert_eq!(
            interrupted_note(Path::new("s.arrow"), 3000, Some(3000)),
            None
        );
        assert_eq!(interrupted_note(Path::new("s.arrow"), 3000, None), None);
        let whole = arrow_schema::Metadata::from([("touchdown.samples", "3000")]);
        assert_eq!(samples_asked(|k| whole.get(k)), Some(3000));
        let shard = arrow_schema::Metadata::from([
            ("touchdown.samples", "3000"),
            ("touchdown.sample_range", "1000..2000"),
        ]);
        assert_eq!(samples_asked(|k| shard.get(k)), Some(1000));
    }
}
