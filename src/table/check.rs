//! The first pass over a table: every cell read and checked as it streams, nothing kept
//! but what the sweep needs to know of the whole table (its rows, each value column's
//! range, the type of each kept CSV column, where its blocks start) and the terrain
//! columns held to the surface.

use super::cells::{CellError, CsvKind, arrow_cells, csv_cell};
use super::role::Role;
use super::sink::Sink;
use super::source::{Chunk, Head, Kind, Marks, Rows};
use crate::scenario::{INPUT_FIELDS, Parameter, Scenario, VALUES};
use anyhow::{anyhow, bail};
use arrow_array::Array;
use arrow_schema::DataType;
use std::path::Path;

/// Rows of a block of the table as the sweep reads it (`rows::FileRows`).
pub(super) const BLOCK_ROWS: u64 = 16_384;

/// The most bytes of text a kept text column may hold: an Arrow text column's offsets
/// are 32-bit.
const MAX_TEXT_BYTES: u64 = i32::MAX as u64;

/// What the first pass found.
pub(super) struct Checked {
    /// Rows of the table.
    pub(super) rows: u64,
    /// The least and greatest value of each value column (`Sample::values`) the table has.
    pub(super) ranges: [Option<(f64, f64)>; VALUES],
    /// Where the reader may start (the CSV record of every `BLOCK_ROWS`-th row, the
    /// first row of every Arrow record batch).
    pub(super) marks: Marks,
    /// The Arrow type of each kept CSV column (by column; none for the others).
    pub(super) csv_types: Vec<Option<DataType>>,
}

/// The first offending row of a terrain column (and its value), under each rule.
#[derive(Default)]
struct Firsts {
    /// The first row whose value is not 0.
    nonzero: Option<(u64, f64)>,
    /// The first row out of its range on a rough surface.
    outside: Option<(u64, f64)>,
}

impl Firsts {
    fn take(&mut self, row: u64, x: f64, inside: bool) {
        if x != 0.0 && self.nonzero.is_none() {
            self.nonzero = Some((row, x));
        }
        if !inside && self.outside.is_none() {
            self.outside = Some((row, x));
        }
    }
}

/// Feeds the cells of `chunk`, whose first row is `first`, to `sinks` (each with its
/// column: the field of a CSV record, the place in the batch of an Arrow chunk); kept
/// columns are left to the caller.
pub(super) fn fill(
    chunk: &Chunk,
    first: u64,
    names: &[String],
    sinks: &mut [(usize, Sink)],
    path: &Path,
) -> anyhow::Result<()> {
    match chunk {
        Chunk::Csv(records) => {
            for (i, (record, line)) in records.iter().enumerate() {
                let row = first + i as u64;
                for (j, sink) in sinks.iter_mut().filter(|(_, s)| !s.is_kept()) {
                    sink.take(row, csv_cell(&record[*j])).map_err(|why| {
                        anyhow!(
                            "{}: row {row} (line {line}), column {}: {why}",
                            path.display(),
                            names[*j]
                        )
                    })?;
                }
            }
        }
        Chunk::Batch(b) => {
            for (c, (j, sink)) in sinks.iter_mut().enumerate() {
                if sink.is_kept() {
                    continue;
                }
                let name = &names[*j];
                arrow_cells(b.column(c), &mut |i, cell| {
                    let row = first + i as u64;
                    sink.take(row, cell).map_err(|why| {
                        anyhow!("{}: row {row}, column {name}: {why}", path.display())
                    })
                })
                .map_err(|e| match e {
                    CellError::Type(t) => anyhow!(
                        "{}: column {name} is of type {t}: its values must be numbers",
                        path.display()
                    ),
                    CellError::At(e) => e,
                })?;
            }
        }
    }
    Ok(())
}

/// Bytes of text in a kept Arrow column of 32-bit offsets (none for other types).
fn text_bytes(a: &dyn Array) -> u64 {
    use arrow_array::cast::AsArray;
    let span = |o: &[i32]| (o[o.len() - 1] - o[0]) as u64;
    match a.data_type() {
        DataType::Utf8 => span(a.as_string::<i32>().value_offsets()),
        DataType::Binary => span(a.as_binary::<i32>().value_offsets()),
        _ => 0,
    }
}

/// Reads and checks every cell of the table at `path` (its head `head`, its columns'
/// `roles`) for a sweep of `scenario`.
pub(super) fn check(
    path: &Path,
    head: &Head,
    roles: &[Role],
    scenario: &Scenario,
) -> anyhow::Result<Checked> {
    let mut sinks: Vec<(usize, Sink)> = roles.iter().map(|&r| Sink::new(r)).enumerate().collect();
    let mut ranges = [None; VALUES];
    let mut kinds: Vec<Option<CsvKind>> = roles
        .iter()
        .map(|&r| (r == Role::Kept && head.kind == Kind::Csv).then(CsvKind::new))
        .collect();
    let mut text = vec![0u64; roles.len()];
    let (mut tiles, mut offsets) = (Firsts::default(), [Firsts::default(), Firsts::default()]);
    let rough = &scenario.surface.roughness;
    let mut marks = Marks::default();
    let mut reader = Rows::open(path, head, &marks.clone(), BLOCK_ROWS, 0, None)?;
    let mut first = 0u64;
    while let Some(chunk) = reader.next_chunk(path, usize::MAX)? {
        match &chunk {
            Chunk::Csv(records) => {
                for (i, (record, _)) in records.iter().enumerate() {
                    if (first + i as u64).is_multiple_of(BLOCK_ROWS) {
                        marks.csv.extend(record.position().cloned());
                    }
                    for (j, k) in kinds.iter_mut().enumerate() {
                        if let Some(k) = k {
                            k.take(&record[j]);
                        }
                    }
                }
            }
            Chunk::Batch(b) => {
                if head.kind == Kind::ArrowFile {
                    marks.batches.push(first);
                }
                for (j, t) in text.iter_mut().enumerate() {
                    if roles[j] == Role::Kept {
                        *t += text_bytes(b.column(j).as_ref());
                    }
                }
            }
        }
        fill(&chunk, first, &head.names, &mut sinks, path)?;
        for (_, sink) in &mut sinks {
            match sink {
                Sink::Value(k, v) => {
                    for &x in v.iter() {
                        let (a, b) = ranges[*k].unwrap_or((f64::INFINITY, f64::NEG_INFINITY));
                        ranges[*k] = Some((a.min(x), b.max(x)));
                    }
                }
                Sink::Tile(v) => {
                    for (i, &t) in v.iter().enumerate() {
                        tiles.take(first + i as u64, f64::from(t), (t as usize) < rough.tiles);
                    }
                }
                Sink::Offset(j, v) => {
                    for (i, &x) in v.iter().enumerate() {
                        let inside = (0.0..rough.tile_size_m).contains(&x);
                        offsets[*j].take(first + i as u64, x, inside);
                    }
                }
                _ => {}
            }
            sink.clear();
        }
        first += chunk.rows() as u64;
    }
    if first == 0 {
        bail!("{}: the table has no rows", path.display());
    }
    for (j, k) in kinds.iter().enumerate() {
        text[j] += k.map_or(0, |k| k.text_bytes);
        if text[j] > MAX_TEXT_BYTES && k.is_none_or(|k| k.data_type() == DataType::Utf8) {
            bail!(
                "{}: column {} holds {} bytes of text, more than the 2 GiB (2147483647 \
                 bytes) a kept text column may hold: drop it, shorten it, or split the \
                 table",
                path.display(),
                head.names[j],
                text[j]
            );
        }
    }
    let k = INPUT_FIELDS.len() + Parameter::RmsHeightM as usize;
    let largest = ranges[k].map_or_else(|| scenario.rms_height_max_m(), |(_, b)| b.max(0.0));
    check_terrain(path, scenario, largest, &tiles, &offsets)?;
    Ok(Checked {
        rows: first,
        ranges,
        marks,
        csv_types: kinds.iter().map(|k| k.map(|k| k.data_type())).collect(),
    })
}

/// The terrain columns against the surface the sweep will have (`largest`: its largest
/// roughness): a tile the rough surface has and an offset inside it, or 0 where the
/// surface is flat.
fn check_terrain(
    path: &Path,
    scenario: &Scenario,
    largest: f64,
    tiles: &Firsts,
    offsets: &[Firsts; 2],
) -> anyhow::Result<()> {
    let rough = &scenario.surface.roughness;
    let where_ = |(row, _): (u64, f64), name: &str, what: String| {
        anyhow!("{}: row {row}, column {name}: {what}", path.display())
    };
    if largest == 0.0
        && let Some(at @ (_, t)) = tiles.nonzero
    {
        return Err(where_(
            at,
            "terrain_tile",
            format!("{t}, but the surface is flat (its only tile is 0)"),
        ));
    }
    if largest > 0.0
        && let Some(at @ (_, t)) = tiles.outside
    {
        return Err(where_(
            at,
            "terrain_tile",
            format!(
                "{t}, but the surface has tiles 0 to {} (surface.roughness.tiles)",
                rough.tiles - 1
            ),
        ));
    }
    for (j, name) in ["terrain_offset_u_m", "terrain_offset_v_m"]
        .iter()
        .enumerate()
    {
        if largest == 0.0
            && let Some(at @ (_, x)) = offsets[j].nonzero
        {
            return Err(where_(
                at,
                name,
                format!("{x}, but the surface is flat (the offset is 0)"),
            ));
        }
        if largest > 0.0
            && let Some(at @ (_, x)) = offsets[j].outside
        {
            return Err(where_(
                at,
                name,
                format!(
                    "{x} is outside the tile: values from 0 up to, not including, {} m \
                     (surface.roughness.tile_size_m)",
                    rough.tile_size_m
                ),
            ));
        }
    }
    Ok(())
}
