//! Any touchdown file read back as named columns (a sweep, shard, trace or study file, Arrow
//! IPC or Parquet, or a sweep held in memory), for what draws or tabulates it.

use crate::output::read::{Batches, Texts, format_of, open, outcome_of};
use anyhow::anyhow;
use arrow_array::cast::AsArray;
use arrow_array::types::Float64Type;
use arrow_schema::{DataType, SchemaRef};
use std::collections::HashMap;
use std::path::Path;

/// Columns of a touchdown file, as `f64` (nulls as NaN), with the schema metadata, the
/// outcome column (as indices into `Outcome::ALL`) when the file has one, and the other
/// text columns (a trace's control phase).
pub struct Table {
    /// The schema metadata (the file's provenance, `touchdown.*` keys).
    pub meta: HashMap<String, String>,
    /// The numeric columns kept, by name, as `f64` (nulls as NaN).
    pub columns: HashMap<String, Vec<f64>>,
    /// Each row's outcome, as an index into `Outcome::ALL`; empty without an outcome column.
    pub outcome: Vec<u8>,
    /// The other text columns kept, by name (a trace's control phase).
    pub texts: HashMap<String, Vec<String>>,
    /// Rows in the file.
    pub rows: usize,
}

impl Table {
    /// Reads the numeric and text columns `wanted` keeps (and the outcome column) of the
    /// file at `path`.
    pub fn read(path: &Path, wanted: impl Fn(&str) -> bool) -> anyhow::Result<Table> {
        let format = format_of(path)?;
        let (schema, batches) = open(path, format)?;
        Table::of_batches(&schema, batches, path, wanted)
    }

    /// The columns `wanted` keeps (and the outcome column) of `batches` with `schema`,
    /// read from the file (or the sweep in memory) that errors name `path`.
    pub fn of_batches(
        schema: &SchemaRef,
        batches: Batches,
        path: &Path,
        wanted: impl Fn(&str) -> bool,
    ) -> anyhow::Result<Table> {
        let meta: HashMap<String, String> = schema
            .metadata()
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        let mut columns: HashMap<String, Vec<f64>> = HashMap::new();
        let mut outcome = Vec::new();
        let mut texts: HashMap<String, Vec<String>> = HashMap::new();
        let mut rows = 0;
        for b in batches {
            let b = b?;
            rows += b.num_rows();
            for (field, array) in b.schema().fields().iter().zip(b.columns()) {
                let name = field.name();
                if name == "outcome" {
                    let s = Texts::of(array.as_ref()).ok_or_else(|| {
                        anyhow!("{}: the outcome column is not text", path.display())
                    })?;
                    for v in s.iter() {
                        outcome.push(outcome_of(v.unwrap_or(""), path)? as u8);
                    }
                    continue;
                }
                if !wanted(name) {
                    continue;
                }
                if let Some(s) = Texts::of(array.as_ref()) {
                    texts
                        .entry(name.clone())
                        .or_default()
                        .extend(s.iter().map(|v| v.unwrap_or("").to_string()));
                    continue;
                }
                let values: Vec<f64> = match array.data_type() {
                    DataType::Float64 => array
                        .as_primitive::<Float64Type>()
                        .iter()
                        .map(|v| v.unwrap_or(f64::NAN))
                        .collect(),
                    _ => continue,
                };
                columns.entry(name.clone()).or_default().extend(values);
            }
        }
        Ok(Table {
            meta,
            columns,
            outcome,
            texts,
            rows,
        })
    }

    /// A column by name, or an error naming the file and the column.
    pub fn column(&self, name: &str, path: &Path) -> anyhow::Result<&[f64]> {
        self.columns
            .get(name)
            .map(Vec::as_slice)
            .ok_or_else(|| anyhow!("{}: no Float64 column {name}", path.display()))
    }

    /// The legs of the lander, from the per-leg columns that `suffix` ends.
    pub fn legs(&self, suffix: &str) -> usize {
        (0..)
            .take_while(|k| self.columns.contains_key(&format!("leg{k}_{suffix}")))
            .count()
    }
}
