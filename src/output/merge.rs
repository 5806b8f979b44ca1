//! `touchdown merge`: the shard files of one sweep joined into the file that the sweep
//! writes when it runs in one process: the same schema and metadata, the rows in sample
//! order, cut into the same batches. Shards that do not belong together are refused before
//! anything is written.

use super::format::Format;
use super::read::{format_of, open};
use super::sweep::{Rebatcher, SHARD_KEYS, SweepInfo, SweepWriter, schema};
use crate::sweep::Shard;
use anyhow::{anyhow, bail};
use arrow_array::{Array, UInt64Array};
use arrow_schema::SchemaRef;
use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Schema metadata that every shard of one sweep shares, with what a message calls it.
const SHARED_KEYS: [(&str, &str); 8] = [
    ("touchdown.kind", "kind of file"),
    ("touchdown.engine", "engine version"),
    (
        "touchdown.lane_type",
        "kernel arithmetic (f64x8-fma, f64x8-nofma, f32x16-fma or f32x16-nofma)",
    ),
    ("touchdown.seed", "seed"),
    ("touchdown.samples", "sample count"),
    ("touchdown.scenario", "scenario"),
    (
        "touchdown.inputs.sha256",
        "table of inputs (--inputs; the SHA-256 of its file)",
    ),
    ("touchdown.inputs.keep_columns", "--keep-columns"),
];

/// A shard file, as its schema describes it.
struct ShardFile {
    path: PathBuf,
    format: Format,
    schema: SchemaRef,
    shard: Shard,
    range: Range<u64>,
}

/// What `merge` did.
pub struct Merged {
    /// Shard files joined.
    pub shards: usize,
    /// Rows written: the samples of the whole sweep.
    pub rows: u64,
}

/// Joins `shards` (in any order) into `out`, written as `format`.
pub fn merge(shards: &[PathBuf], out: &Path, format: Format) -> anyhow::Result<Merged> {
    super::check_output_path(out)?;
    let files = shards
        .iter()
        .map(|p| open_shard(p))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let first = &files[0];
    for f in &files[1..] {
        check_same_sweep(first, f)?;
    }
    let files = in_shard_order(files)?;

    let control: Vec<&'static str> = super::sweep::CONTROL_COLUMNS
        .iter()
        .map(|c| c.0)
        .filter(|name| files[0].schema.field_with_name(name).is_ok())
        .collect();
    let parameters: Vec<&'static str> = crate::scenario::PARAMETER_FIELDS
        .iter()
        .chain(&crate::scenario::INITIAL_FIELDS)
        .map(|c| c.0)
        .filter(|name| files[0].schema.field_with_name(name).is_ok())
        .collect();
    let meta = files[0].schema.metadata();
    let text = |key: &str| meta.get(key).map_or("", String::as_str);
    let table: Vec<(String, String)> = crate::scenario::METADATA_KEYS
        .iter()
        .filter_map(|k| meta.get(k).map(|v| ((*k).to_string(), v.clone())))
        .collect();
    let mut info = SweepInfo {
        scenario_toml: text("touchdown.scenario"),
        seed: number(&files[0], "touchdown.seed")?,
        samples: number(&files[0], "touchdown.samples")?,
        lane_type: text("touchdown.lane_type"),
        shard: None,
        control: &control,
        parameters: &parameters,
        table: &table,
        kept: &[],
    };
    let legs = super::sweep::leg_count(&files[0].schema);
    // The columns passed through from a table of inputs come after the sweep's own.
    let own = schema(legs, &info).fields().len();
    let kept: Vec<arrow_schema::FieldRef> =
        files[0].schema.fields().iter().skip(own).cloned().collect();
    info.kept = &kept;
    let whole = schema(legs, &info);
    for f in &files {
        if !super::sweep::same_columns(f.schema.fields(), whole.fields()) {
            bail!(
                "{} does not hold the columns of a sweep of this engine (another version?)",
                f.path.display()
            );
        }
    }

    let mut writer = SweepWriter::create(out, format, legs, &info)?;
    let mut batches = Rebatcher::new(whole);
    for f in &files {
        copy_rows(f, &mut batches, &mut writer)?;
    }
    batches.finish(&mut writer)?;
    let rows = writer.finish()?;
    Ok(Merged {
        shards: files.len(),
        rows,
    })
}

/// The schema of a shard file, checked to be one.
fn open_shard(path: &Path) -> anyhow::Result<ShardFile> {
    let format = format_of(path)?;
    let (schema, _) = open(path, format)?;
    let meta = schema.metadata().clone();
    let Some(kind) = meta.get("touchdown.kind") else {
        bail!(
            "{} is not a file of touchdown (no touchdown.kind in its schema metadata)",
            path.display()
        );
    };
    if kind != "sweep" {
        bail!("{} is a {kind} file, not a sweep shard", path.display());
    }
    let Some(shard) = meta.get(SHARD_KEYS[0]) else {
        bail!(
            "{} is a whole sweep, not a shard: it was not written with --shard",
            path.display()
        );
    };
    let shard: Shard = shard
        .parse()
        .map_err(|e| anyhow!("{}: bad {}: {e}", path.display(), SHARD_KEYS[0]))?;
    let mut file = ShardFile {
        path: path.to_path_buf(),
        format,
        schema,
        shard,
        range: 0..0,
    };
    file.range = shard.range(number(&file, "touchdown.samples")?);
    let stated = meta.get(SHARD_KEYS[1]).map_or("", String::as_str);
    if stated != format!("{}..{}", file.range.start, file.range.end) {
        bail!(
            "{}: shard {shard} of {} samples covers {:?}, but the file says {}",
            path.display(),
            number(&file, "touchdown.samples")?,
            file.range,
            stated
        );
    }
    Ok(file)
}

/// A whole number from the schema metadata of `f`.
fn number(f: &ShardFile, key: &str) -> anyhow::Result<u64> {
    let value = f.schema.metadata().get(key).map_or("", String::as_str);
    value.parse().map_err(|_| {
        anyhow!(
            "{}: {key} = {value:?} in its schema metadata is not a whole number",
            f.path.display()
        )
    })
}

/// Refuses `b` unless it is a shard of the same sweep as `a`.
fn check_same_sweep(a: &ShardFile, b: &ShardFile) -> anyhow::Result<()> {
    let (ma, mb) = (a.schema.metadata(), b.schema.metadata());
    for (key, what) in SHARED_KEYS {
        let (x, y) = (ma.get(key), mb.get(key));
        if x != y {
            let shown = |v: Option<&String>| match v {
                Some(v) if v.len() <= 64 && !v.contains('\n') => format!("{v:?}"),
                Some(_) => "another".to_string(),
                None => "none".to_string(),
            };
            bail!(
                "{} and {} are not shards of one sweep: their {what} differs ({} against {})",
                a.path.display(),
                b.path.display(),
                shown(x),
                shown(y)
            );
        }
    }
    if a.shard.count != b.shard.count {
        bail!(
            "{} and {} are not shards of one sweep: shard {} against shard {} (different shard counts)",
            a.path.display(),
            b.path.display(),
            a.shard,
            b.shard
        );
    }
    Ok(())
}

/// The shards sorted by index, each exactly once and none missing.
fn in_shard_order(files: Vec<ShardFile>) -> anyhow::Result<Vec<ShardFile>> {
    let count = files[0].shard.count;
    let mut by_index: BTreeMap<u64, ShardFile> = BTreeMap::new();
    for f in files {
        if let Some(other) = by_index.get(&f.shard.index) {
            bail!(
                "shard {} is given twice: {} and {}",
                f.shard,
                other.path.display(),
                f.path.display()
            );
        }
        by_index.insert(f.shard.index, f);
    }
    let missing: Vec<String> = (0..count)
        .filter(|k| !by_index.contains_key(k))
        .map(|index| Shard { index, count }.to_string())
        .collect();
    if !missing.is_empty() {
        bail!(
            "the sweep has {count} shards; missing: {}",
            missing.join(", ")
        );
    }
    Ok(by_index.into_values().collect())
}

/// Copies the rows of `f` into `batches`, checking that they are its samples, in order.
fn copy_rows(
    f: &ShardFile,
    batches: &mut Rebatcher,
    writer: &mut SweepWriter,
) -> anyhow::Result<()> {
    let mut next = f.range.start;
    for b in open(&f.path, f.format)?.1 {
        let b = b?;
        let samples = b
            .columns()
            .first()
            .and_then(|c| c.as_any().downcast_ref::<UInt64Array>())
            .ok_or_else(|| anyhow!("{}: the sample column is not u64", f.path.display()))?;
        for s in samples.values() {
            if *s != next || next >= f.range.end {
                bail!(
                    "{}: holds sample {s} where shard {} has sample {next} of {:?}",
                    f.path.display(),
                    f.shard,
                    f.range
                );
            }
            next += 1;
        }
        batches.push(b, writer)?;
    }
    if next != f.range.end {
        bail!(
            "{} ends at sample {next}, but shard {} runs to {}: the file is incomplete",
            f.path.display(),
            f.shard,
            f.range.end
        );
    }
    Ok(())
}
