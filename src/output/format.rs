//! The formats of a sweep file and the size of its record batches, which every writer and
//! reader of sweep files shares.

/// Rows per record batch (and Parquet row group).
pub const BATCH_ROWS: usize = 8_192;

/// File formats of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// Arrow IPC file (Feather v2): `pandas.read_feather`, `polars.read_ipc`.
    Arrow,
    /// Parquet: `pandas.read_parquet`, `polars.read_parquet`.
    Parquet,
}

impl Format {
    /// The name `--format` takes.
    #[must_use]
    pub fn key(self) -> &'static str {
        match self {
            Format::Arrow => "arrow",
            Format::Parquet => "parquet",
        }
    }
}
