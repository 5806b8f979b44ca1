//! The rows of a checked table as the sweep asks for them: read from the file in blocks
//! of `BLOCK_ROWS`, in order as the sweep goes (one reader, kept from block to block). A
//! sweep asks for each row once: a block's values are forgotten once every row of it has
//! been asked for, its kept columns once the sweep has written its rows. Memory holds a
//! block or two of values, and the kept columns of the rows in flight, whatever the
//! table's size.

use super::cells::csv_array;
use super::check::{BLOCK_ROWS, fill};
use super::role::Role;
use super::sink::Sink;
use super::source::{Chunk, Head, Marks, Rows};
use crate::scenario::{RowSource, TableRow};
use arrow_array::{Array, ArrayRef};
use arrow_schema::{DataType, Field, FieldRef};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Blocks held at most, against a caller that asks for rows far apart: more than a sweep
/// has in flight (two windows of samples and a batch of the output, with 64 threads); a
/// block dropped for room is read again if asked for.
const MAX_BLOCKS: usize = 64;

/// The file's size and time of change, as when it was checked.
type Stamp = (u64, Option<std::time::SystemTime>);

fn stamp(path: &Path) -> Option<Stamp> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.len(), m.modified().ok()))
}

/// One block of rows: the values of each column the sweep takes, and the kept columns.
struct Block {
    first: u64,
    rows: usize,
    /// Rows asked for so far: at `rows`, the values go.
    asked: usize,
    /// The values (dropped once every row was asked for: `forgotten`).
    sinks: Vec<(usize, Sink)>,
    forgotten: bool,
    kept: Vec<ArrayRef>,
}

/// The reader, the blocks held, and what went wrong.
struct State {
    reader: Option<Rows>,
    blocks: Vec<Block>,
    /// Rows below this are written: their blocks go.
    written: u64,
    /// Why a block could not be read.
    failed: Option<String>,
}

/// A checked table's rows, read from its file as the sweep asks for them.
pub(super) struct FileRows {
    path: PathBuf,
    head: Head,
    marks: Marks,
    rows: u64,
    /// The columns the sweep reads, in the file's order (the reader's projection).
    columns: Vec<usize>,
    roles: Vec<Role>,
    /// The fields of the kept columns, and the type of each kept CSV column.
    kept_fields: Vec<FieldRef>,
    stamp: Option<Stamp>,
    state: Mutex<State>,
}

impl FileRows {
    /// The rows of the table at `path`, checked (`check::check`), with its columns' roles.
    pub(super) fn new(
        path: &Path,
        head: Head,
        marks: Marks,
        rows: u64,
        roles: &[Role],
        csv_types: &[Option<DataType>],
    ) -> FileRows {
        let columns: Vec<usize> = (0..roles.len())
            .filter(|&j| roles[j] != Role::Sample)
            .collect();
        let kept_fields = columns
            .iter()
            .filter(|&&j| roles[j] == Role::Kept)
            .map(|&j| match &csv_types[j] {
                Some(t) => Arc::new(Field::new(&head.names[j], t.clone(), true)),
                None => head.fields[j].clone(),
            })
            .collect();
        FileRows {
            path: path.to_path_buf(),
            head,
            marks,
            rows,
            roles: columns.iter().map(|&j| roles[j]).collect(),
            columns,
            kept_fields,
            stamp: stamp(path),
            state: Mutex::new(State {
                reader: None,
                blocks: Vec::new(),
                written: 0,
                failed: None,
            }),
        }
    }

    /// Reads block `b` with `state`'s reader (opened again unless it stands at the block).
    fn read_block(&self, state: &mut State, b: u64) -> anyhow::Result<Block> {
        if stamp(&self.path) != self.stamp {
            anyhow::bail!(
                "the input table {} changed while the sweep read it",
                self.path.display()
            );
        }
        let first = b * BLOCK_ROWS;
        let rows = BLOCK_ROWS.min(self.rows - first) as usize;
        let mut reader = match state.reader.take() {
            Some(r) if r.at == first => r,
            _ => Rows::open(
                &self.path,
                &self.head,
                &self.marks,
                BLOCK_ROWS,
                first,
                Some(&self.columns),
            )?,
        };
        let mut sinks: Vec<(usize, Sink)> = self
            .columns
            .iter()
            .zip(&self.roles)
            .map(|(&j, &r)| (j, Sink::new(r)))
            .collect();
        let kept_at: Vec<usize> = (0..self.columns.len())
            .filter(|&c| self.roles[c] == Role::Kept)
            .collect();
        let mut pieces: Vec<Vec<ArrayRef>> = vec![Vec::new(); kept_at.len()];
        let mut done = 0;
        while done < rows {
            let Some(chunk) = reader.next_chunk(&self.path, rows - done)? else {
                anyhow::bail!(
                    "the input table {} ends at row {}, before its {} rows",
                    self.path.display(),
                    first + done as u64,
                    self.rows
                );
            };
            fill(
                &chunk,
                first + done as u64,
                &self.head.names,
                &mut sinks,
                &self.path,
            )?;
            for (k, &c) in kept_at.iter().enumerate() {
                pieces[k].push(match &chunk {
                    Chunk::Csv(records) => csv_array(
                        self.kept_fields[k].data_type(),
                        records.iter().map(|(r, _)| &r[self.columns[c]]),
                    ),
                    Chunk::Batch(batch) => batch.column(c).clone(),
                });
            }
            done += chunk.rows();
        }
        state.reader = Some(reader);
        let kept = pieces
            .iter()
            .map(|p| {
                let p: Vec<&dyn Array> = p.iter().map(AsRef::as_ref).collect();
                arrow_select::concat::concat(&p)
            })
            .collect::<Result<_, _>>()?;
        Ok(Block {
            first,
            rows,
            asked: 0,
            sinks,
            forgotten: false,
            kept,
        })
    }

    /// The place in `state.blocks` of the block of row `row`, read if it is not held (or,
    /// for its `values`, if they are gone).
    fn block_of(&self, state: &mut State, row: u64, values: bool) -> anyhow::Result<usize> {
        let b = row / BLOCK_ROWS;
        if let Some(i) = state.blocks.iter().position(|k| k.first == b * BLOCK_ROWS) {
            if !values || !state.blocks[i].forgotten {
                return Ok(i);
            }
            state.blocks.remove(i);
        }
        let written = state.written;
        state.blocks.retain(|k| k.first + k.rows as u64 > written);
        if state.blocks.len() >= MAX_BLOCKS {
            state.blocks.remove(0);
        }
        let block = self.read_block(state, b)?;
        state.blocks.push(block);
        Ok(state.blocks.len() - 1)
    }
}

impl RowSource for FileRows {
    fn row(&self, row: u64) -> TableRow {
        let mut state = self
            .state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let mut out = TableRow::default();
        if state.failed.is_some() || row >= self.rows {
            return out;
        }
        match self.block_of(&mut state, row, true) {
            Ok(i) => {
                let block = &mut state.blocks[i];
                let at = (row - block.first) as usize;
                for (_, sink) in &block.sinks {
                    sink.give(at, &mut out);
                }
                block.asked += 1;
                if block.asked == block.rows {
                    block.sinks = Vec::new();
                    block.forgotten = true;
                }
            }
            Err(e) => state.failed = Some(format!("{e:#}")),
        }
        out
    }

    fn kept_fields(&self) -> Vec<FieldRef> {
        self.kept_fields.clone()
    }

    fn kept_rows(&self, first: u64, rows: usize) -> anyhow::Result<Vec<ArrayRef>> {
        let mut state = self
            .state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(why) = &state.failed {
            anyhow::bail!("{why}");
        }
        let mut pieces: Vec<Vec<ArrayRef>> = vec![Vec::new(); self.kept_fields.len()];
        let end = first + rows as u64;
        let mut at = first;
        while at < end && !self.kept_fields.is_empty() {
            let i = self.block_of(&mut state, at, false)?;
            let block = &state.blocks[i];
            let from = (at - block.first) as usize;
            let take = (block.rows - from).min((end - at) as usize);
            for (p, a) in pieces.iter_mut().zip(&block.kept) {
                p.push(a.slice(from, take));
            }
            at += take as u64;
        }
        state.written = state.written.max(end);
        pieces
            .iter()
            .map(|p| {
                let p: Vec<&dyn Array> = p.iter().map(AsRef::as_ref).collect();
                Ok(arrow_select::concat::concat(&p)?)
            })
            .collect()
    }
}
