//! A table of the user's own inputs (`sweep --inputs TABLE`), as data: row `i` gives sample
//! `i` the values of its columns. `crate::table` reads and checks the files.

use super::inputs::VALUES;
use super::inputs::value_name;
use super::sample::Sample;
use arrow_array::ArrayRef;
use arrow_schema::FieldRef;
use std::path::PathBuf;

/// A table of inputs, read and checked.
pub struct InputTable {
    /// The file, as the command line named it.
    pub path: PathBuf,
    /// `csv`, `arrow` or `parquet`.
    pub format: &'static str,
    /// SHA-256 of the file's bytes, in hexadecimal (as `sha256sum` prints it).
    pub sha256: String,
    /// Rows of the table: samples of the sweep.
    pub rows: u64,
    /// The columns it was read with, in the table's order.
    pub columns: Vec<String>,
    /// Whether the columns unknown to the sweep pass through (`--keep-columns`).
    pub keep_columns: bool,
    /// Where its rows come from: the file, read in blocks as the sweep goes, or rows in
    /// memory (`from_samples`).
    pub(crate) source: Box<dyn RowSource>,
}

impl std::fmt::Debug for InputTable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InputTable")
            .field("path", &self.path)
            .field("sha256", &self.sha256)
            .field("rows", &self.rows)
            .field("columns", &self.columns)
            .finish_non_exhaustive()
    }
}

/// Two tables are the same table when their files have the same bytes and are read the same
/// way.
impl PartialEq for InputTable {
    fn eq(&self, other: &Self) -> bool {
        self.sha256 == other.sha256 && self.keep_columns == other.keep_columns
    }
}

/// Schema metadata keys of a sweep that ran a table (`InputTable::metadata`).
pub const METADATA_KEYS: [&str; 5] = [
    "touchdown.inputs.file",
    "touchdown.inputs.sha256",
    "touchdown.inputs.rows",
    "touchdown.inputs.columns",
    "touchdown.inputs.keep_columns",
];

/// What one row of a table gives a sample, where the table has the column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableRow {
    /// Value `k` of the sample (`Sample::values`).
    pub values: [Option<f64>; VALUES],
    /// Its generator seed.
    pub sample_seed: Option<u64>,
    /// Its terrain tile.
    pub terrain_tile: Option<u32>,
    /// Its terrain offset, downhill and cross-slope, m.
    pub terrain_offset_m: [Option<f64>; 2],
}

impl Default for TableRow {
    fn default() -> Self {
        TableRow {
            values: [None; VALUES],
            sample_seed: None,
            terrain_tile: None,
            terrain_offset_m: [None; 2],
        }
    }
}

/// Where the rows of a table come from. Rows are asked for from many threads, roughly in
/// order; the columns passed through once per batch of the output, in order.
pub trait RowSource: Send + Sync {
    /// Row `row`. Where the file cannot give it (changed since it was checked), the row
    /// is empty and `kept_rows` says why.
    fn row(&self, row: u64) -> TableRow;
    /// The fields of the columns passed through to the output, in the table's order.
    fn kept_fields(&self) -> Vec<FieldRef>;
    /// The columns passed through, rows `first..first + rows`, as fresh arrays; no row
    /// before `first + rows` is asked for again by the sweep that asks this. An error if a
    /// row could not be read.
    fn kept_rows(&self, first: u64, rows: usize) -> anyhow::Result<Vec<ArrayRef>>;
}

/// Samples in memory as rows: every value, the seed and the terrain.
struct SampleRows(Vec<Sample>);

impl RowSource for SampleRows {
    fn row(&self, row: u64) -> TableRow {
        let s = &self.0[row as usize];
        TableRow {
            values: s.values().map(Some),
            sample_seed: Some(s.seed),
            terrain_tile: Some(s.terrain_tile),
            terrain_offset_m: s.terrain_offset_m.map(Some),
        }
    }

    fn kept_fields(&self) -> Vec<FieldRef> {
        Vec::new()
    }

    fn kept_rows(&self, _: u64, _: usize) -> anyhow::Result<Vec<ArrayRef>> {
        Ok(Vec::new())
    }
}

impl InputTable {
    /// What row `row` gives its sample.
    #[must_use]
    pub fn row(&self, row: u64) -> TableRow {
        self.source.row(row)
    }

    /// The fields of the columns passed through to the output, in the table's order.
    #[must_use]
    pub fn kept_fields(&self) -> Vec<FieldRef> {
        self.source.kept_fields()
    }

    /// The columns passed through to the output, rows `first..first + rows`, as fresh
    /// arrays (not slices: the file's bytes do not depend on where a batch was cut from).
    /// A sweep asks for them in order, once per batch, and no row before `first + rows`
    /// again.
    pub fn kept_rows(&self, first: u64, rows: usize) -> anyhow::Result<Vec<ArrayRef>> {
        self.source.kept_rows(first, rows)
    }

    /// What a sweep's metadata says of the table (`METADATA_KEYS`).
    #[must_use]
    pub fn metadata(&self) -> Vec<(String, String)> {
        let values = [
            self.path.display().to_string(),
            self.sha256.clone(),
            self.rows.to_string(),
            self.columns.join(","),
            self.keep_columns.to_string(),
        ];
        METADATA_KEYS
            .iter()
            .zip(values)
            .map(|(k, v)| ((*k).to_string(), v))
            .collect()
    }

    /// A table in memory that replays `samples` exactly, row `i` sample `i`: every value
    /// (`Sample::values`), the generator seed and the terrain tile and offset. `boundary`
    /// runs its candidates through the kernels this way, each with its slope redrawn.
    #[must_use]
    pub fn from_samples(samples: Vec<Sample>) -> InputTable {
        InputTable {
            path: PathBuf::from("(boundary search)"),
            format: "memory",
            sha256: String::new(),
            rows: samples.len() as u64,
            columns: (0..VALUES)
                .map(|k| value_name(k).to_string())
                .chain(
                    [
                        "sample_seed",
                        "terrain_tile",
                        "terrain_offset_u_m",
                        "terrain_offset_v_m",
                    ]
                    .map(String::from),
                )
                .collect(),
            keep_columns: false,
            source: Box::new(SampleRows(samples)),
        }
    }
}
