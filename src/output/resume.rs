//! Interrupted sweeps: a sweep stopped by SIGINT, SIGTERM or SIGHUP closes its file as a
//! valid one under `OUT.interrupted` (never under `OUT`, which only a complete sweep
//! takes), and `sweep --resume OUT` reads its settings and rows back from there to finish
//! the sweep.

use super::ENGINE;
use super::format::Format;
use super::interrupted_path;
use super::read::Texts;
use super::read::{format_of, open};
use super::sweep::{Rebatcher, SHARD_KEYS, SweepWriter};
use crate::sweep::Shard;
use anyhow::{anyhow, bail};
use arrow_array::{Array, UInt64Array};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The rows a resumed sweep took over, counted by outcome and broken limits (their names as
/// `limits_broken` writes them, empty without that column).
pub type KeptCounts = HashMap<(String, String), u64>;

/// An interrupted sweep, as its file describes it.
pub struct Interrupted {
    /// The interrupted file (`OUT.interrupted`).
    pub path: PathBuf,
    /// Its format, Arrow IPC or Parquet.
    pub format: Format,
    /// The scenario's TOML text, as the sweep ran it.
    pub scenario_toml: String,
    /// The sweep's seed.
    pub seed: u64,
    /// Samples of the whole sweep.
    pub samples: u64,
    /// The slice of the sweep it holds, if it is a shard.
    pub shard: Option<Shard>,
    /// The kernel arithmetic it ran (`f64x8-fma`, `f64x8-nofma`, `f32x16-fma` or `f32x16-nofma`), which the resumed sweep must run too.
    pub lane_type: String,
    /// Rows in the file: samples `first..first + rows` of the sweep.
    pub rows: u64,
    /// Its schema metadata (the table of inputs it ran, if any: `table::reattach`).
    pub meta: arrow_schema::Metadata,
}

impl Interrupted {
    /// Reads the interrupted sweep to `out`: its settings and how many rows it holds.
    pub fn read(out: &Path) -> anyhow::Result<Interrupted> {
        let path = interrupted_path(out);
        if !path.exists() {
            let name = out.file_name().unwrap_or_default().to_string_lossy();
            if let Some(stem) = name.strip_suffix(".interrupted") {
                bail!(
                    "--resume takes the output of the sweep, not its interrupted file: \
                     touchdown sweep --resume {}",
                    out.with_file_name(stem).display()
                );
            }
            if out.exists() {
                bail!(
                    "nothing to resume: {} is complete (no {} beside it)",
                    out.display(),
                    path.display()
                );
            }
            bail!(
                "nothing to resume: no interrupted sweep {} (a sweep killed outright leaves \
                 none; run it again)",
                path.display()
            );
        }
        let format = format_of(&path)?;
        let (schema, batches) = open(&path, format)?;
        let meta = schema.metadata();
        let get = |key: &str| -> anyhow::Result<String> {
            meta.get(key).cloned().ok_or_else(|| {
                anyhow!(
                    "{} is not an interrupted sweep of touchdown: no {key} in its schema",
                    path.display()
                )
            })
        };
        let number = |key: &str| -> anyhow::Result<u64> {
            let v = get(key)?;
            v.parse()
                .map_err(|_| anyhow!("{}: {key} = {v:?} is not a whole number", path.display()))
        };
        if get("touchdown.kind")? != "sweep" {
            bail!("{} is not a sweep file", path.display());
        }
        let engine = get("touchdown.engine")?;
        if engine != ENGINE {
            bail!(
                "{} was written by {engine}; this is {ENGINE}, which may not give the same rows: \
                 run the sweep again",
                path.display()
            );
        }
        let shard = match meta.get(SHARD_KEYS[0]) {
            None => None,
            Some(s) => Some(
                s.parse::<Shard>()
                    .map_err(|e| anyhow!("{}: bad {}: {e}", path.display(), SHARD_KEYS[0]))?,
            ),
        };
        let mut rows = 0u64;
        for b in batches {
            rows += b?.num_rows() as u64;
        }
        Ok(Interrupted {
            format,
            scenario_toml: get("touchdown.scenario")?,
            seed: number("touchdown.seed")?,
            samples: number("touchdown.samples")?,
            shard,
            lane_type: get("touchdown.lane_type")?,
            rows,
            meta: meta.clone(),
            path,
        })
    }

    /// The rows that a resumed sweep takes over: every row of the file (those after its
    /// whole batches head the next batch, `SweepWriter::hold`, so that the resumed file is
    /// cut into the same batches as one that never stopped).
    #[must_use]
    pub fn kept_rows(&self) -> u64 {
        self.rows
    }

    /// Copies the first `kept_rows()` rows to `writer`, checking that they are samples
    /// `first..`, in order: the whole batches written, the rows after them held to head the
    /// next. Returns the counts of the copied rows and their lander-steps, for the closing
    /// summary.
    pub fn copy_kept_rows(
        &self,
        first: u64,
        writer: &mut SweepWriter,
    ) -> anyhow::Result<(KeptCounts, u64)> {
        let kept = self.kept_rows();
        let (schema, batches) = open(&self.path, self.format)?;
        if !super::sweep::same_columns(schema.fields(), writer.schema().fields()) {
            bail!(
                "{} does not hold the columns of a sweep of this engine (another version?); \
                 run the sweep again",
                self.path.display()
            );
        }
        let mut rebatcher = Rebatcher::new(writer.schema().clone());
        let (mut counts, mut steps) = (HashMap::new(), 0u64);
        let mut next = first;
        for b in batches {
            if next == first + kept {
                break;
            }
            let b = b?;
            let b = b.slice(0, b.num_rows().min((first + kept - next) as usize));
            let column = |name: &str| {
                b.column_by_name(name)
                    .ok_or_else(|| anyhow!("{}: no column {name}", self.path.display()))
            };
            let samples = column("sample")?.as_any().downcast_ref::<UInt64Array>();
            let outcomes = Texts::of(column("outcome")?.as_ref());
            let step_counts = column("steps")?.as_any().downcast_ref::<UInt64Array>();
            let limits = b
                .column_by_name(super::sweep::LIMITS_COLUMN)
                .map(|c| Texts::of(c.as_ref()));
            let (Some(samples), Some(outcomes), Some(step_counts), limits @ (None | Some(Some(_)))) =
                (samples, outcomes, step_counts, limits)
            else {
                bail!("{}: a column has the wrong type", self.path.display());
            };
            let limits = limits.flatten();
            for s in samples.values() {
                if *s != next {
                    bail!(
                        "{}: holds sample {s} where sample {next} belongs",
                        self.path.display()
                    );
                }
                next += 1;
            }
            for (i, o) in outcomes.iter().enumerate() {
                let broken = limits.as_ref().and_then(|l| l.get(i)).unwrap_or("");
                let key = (o.unwrap_or_default().to_string(), broken.to_string());
                *counts.entry(key).or_insert(0) += 1;
            }
            steps += step_counts.values().iter().sum::<u64>();
            rebatcher.push(b, writer)?;
        }
        rebatcher.hand_over(writer)?;
        Ok((counts, steps))
    }
}
