//! A table of the user's own inputs (`sweep --inputs TABLE`), as data: row `i` gives sample
//! `i` the values of its columns. `crate::table` reads and checks the files.

use super::inputs::VALUES;
use super::inputs::value_name;
use super::sample::Sample;
use arrow_array::{ArrayRef, RecordBatch};
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
    /// The table's column for each value of a sample (`Sample::values`), if it has one.
    pub(crate) values: [Option<Vec<f64>>; VALUES],
    pub(crate) sample_seed: Option<Vec<u64>>,
    pub(crate) terrain_tile: Option<Vec<u32>>,
    pub(crate) terrain_offset_m: [Option<Vec<f64>>; 2],
    /// The columns passed through to the output, in the table's order.
    pub(crate) kept: Option<RecordBatch>,
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

impl InputTable {
    /// Value `k` of a sample (`Sample::values`) of row `row`, where the table gives it.
    #[must_use]
    pub fn value(&self, k: usize, row: u64) -> Option<f64> {
        self.values[k].as_ref().map(|c| c[row as usize])
    }

    /// The generator seed of row `row`, where the table gives it.
    #[must_use]
    pub fn sample_seed(&self, row: u64) -> Option<u64> {
        self.sample_seed.as_ref().map(|c| c[row as usize])
    }

    /// The terrain tile and offset of row `row`, where the table gives them.
    #[must_use]
    pub fn terrain(&self, row: u64) -> (Option<u32>, [Option<f64>; 2]) {
        let i = row as usize;
        (
            self.terrain_tile.as_ref().map(|c| c[i]),
            [0, 1].map(|j| self.terrain_offset_m[j].as_ref().map(|c| c[i])),
        )
    }

    /// The fields of the columns passed through to the output, in the table's order.
    #[must_use]
    pub fn kept_fields(&self) -> Vec<FieldRef> {
        self.kept
            .as_ref()
            .map_or_else(Vec::new, |b| b.schema().fields().iter().cloned().collect())
    }

    /// The columns passed through to the output, rows `first..first + rows`, as fresh
    /// arrays (not slices: the file's bytes do not depend on where a batch was cut from).
    pub fn kept_rows(&self, first: u64, rows: usize) -> anyhow::Result<Vec<ArrayRef>> {
        let Some(b) = &self.kept else {
            return Ok(Vec::new());
        };
        b.columns()
            .iter()
            .map(|c| {
                let piece = c.slice(first as usize, rows);
                Ok(arrow_select::concat::concat(&[piece.as_ref()])?)
            })
            .collect()
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
    pub fn from_samples(samples: &[Sample]) -> InputTable {
        let values: Vec<[f64; VALUES]> = samples.iter().map(Sample::values).collect();
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
            values: std::array::from_fn(|k| Some(values.iter().map(|v| v[k]).collect())),
            sample_seed: Some(samples.iter().map(|s| s.seed).collect()),
            terrain_tile: Some(samples.iter().map(|s| s.terrain_tile).collect()),
            terrain_offset_m: [0, 1]
                .map(|j| Some(samples.iter().map(|s| s.terrain_offset_m[j]).collect())),
            kept: None,
        }
    }
}
