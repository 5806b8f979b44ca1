//! The sweep file: one row per sample (MODEL.md section 9), inputs then results, in sample
//! order, as Arrow IPC or Parquet, written in batches of a fixed row count so that the
//! bytes depend on the scenario and seed alone (not on threads or timing).
//!
//! The folder: `schema` (the columns, their units and the provenance in the metadata;
//! the control loop's in `control`),
//! `batch` (rows as a record batch), `writer` (the file written as rows come, and a
//! rebatcher for files made of other files), `read` (the one reader of sweep files: its
//! metadata, legs, typed columns and outcomes; and of sweeps held in memory).

mod batch;
mod control;
mod read;
mod schema;
mod writer;

pub use batch::{batch, control_value};
pub use control::{CONTROL_COLUMNS, control_columns};
pub use read::{SweepBatch, SweepFile, SweepSource, interrupted_note, leg_count, samples_asked};
pub use schema::{
    LIMITS_COLUMN, SHARD_KEYS, SweepInfo, has_limits, parameter_columns, same_columns, schema,
};
pub use writer::{BatchMaker, Made, Rebatcher, SweepWriter};
