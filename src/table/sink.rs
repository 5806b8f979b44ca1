//! Where the checked values of a column go, by its role.

use super::cells::Cell;
use super::role::Role;
use crate::scenario::{TableRow, check_value};

/// Where a column's checked values go.
pub(super) enum Sink {
    Value(usize, Vec<f64>),
    Seed(Vec<u64>),
    Tile(Vec<u32>),
    Offset(usize, Vec<f64>),
    Sample,
    Kept,
}

impl Sink {
    pub(super) fn new(role: Role) -> Sink {
        match role {
            Role::Value(k) => Sink::Value(k, Vec::new()),
            Role::Seed => Sink::Seed(Vec::new()),
            Role::Tile => Sink::Tile(Vec::new()),
            Role::Offset(j) => Sink::Offset(j, Vec::new()),
            Role::Sample => Sink::Sample,
            Role::Kept => Sink::Kept,
        }
    }

    pub(super) fn is_kept(&self) -> bool {
        matches!(self, Sink::Kept)
    }

    /// Forgets the values taken (once they are counted).
    pub(super) fn clear(&mut self) {
        match self {
            Sink::Value(_, v) | Sink::Offset(_, v) => v.clear(),
            Sink::Seed(v) => v.clear(),
            Sink::Tile(v) => v.clear(),
            Sink::Sample | Sink::Kept => {}
        }
    }

    /// Gives `row` the `i`-th value taken.
    pub(super) fn give(&self, i: usize, row: &mut TableRow) {
        match self {
            Sink::Value(k, v) => row.values[*k] = Some(v[i]),
            Sink::Seed(v) => row.sample_seed = Some(v[i]),
            Sink::Tile(v) => row.terrain_tile = Some(v[i]),
            Sink::Offset(j, v) => row.terrain_offset_m[*j] = Some(v[i]),
            Sink::Sample | Sink::Kept => {}
        }
    }

    /// Takes the cell of row `row`; what is wrong with it, if anything.
    pub(super) fn take(&mut self, row: u64, cell: Cell<'_>) -> Result<(), String> {
        let number = |cell: Cell<'_>| -> Result<f64, String> {
            match cell {
                Cell::Int(i) => Ok(i as f64),
                Cell::Float(x) => Ok(x),
                Cell::Text(t) => Err(format!("{t:?} is not a number")),
                Cell::Null => Err("empty: every row needs a value".into()),
            }
        };
        let whole = |cell: Cell<'_>, what: &str| -> Result<i128, String> {
            match cell {
                Cell::Int(i) => Ok(i),
                // Taken as the whole number it is, however large (1e18: the range of a
                // tile or row then refuses it); i128 holds every float below 2^100.
                Cell::Float(x)
                    if x.fract() == 0.0 && x.abs() < 2f64.powi(100) && what != "seed" =>
                {
                    Ok(x as i128)
                }
                Cell::Float(x) if x.fract() == 0.0 && what != "seed" => {
                    Err(format!("{x} is out of range: far past any {what}"))
                }
                Cell::Float(x) if what == "seed" => Err(format!(
                    "{x} is not a whole number (a seed must be written as an integer: a \
                     floating-point column cannot hold every 64-bit seed)"
                )),
                Cell::Float(x) => Err(format!("{x} is not a whole number")),
                Cell::Text(t) => Err(format!("{t:?} is not a whole number")),
                Cell::Null => Err("empty: every row needs a value".into()),
            }
        };
        match self {
            Sink::Value(k, v) => {
                let x = number(cell)?;
                if !x.is_finite() {
                    return Err(format!("{x} is not a finite number"));
                }
                check_value(*k, x).map_err(|allowed| format!("{x} is out of range: {allowed}"))?;
                v.push(x);
            }
            Sink::Seed(v) => {
                let i = whole(cell, "seed")?;
                v.push(u64::try_from(i).map_err(|_| {
                    format!("{i} is not a seed (a whole number from 0 to 2^64 - 1)")
                })?);
            }
            Sink::Tile(v) => {
                let i = whole(cell, "tile")?;
                v.push(u32::try_from(i).map_err(|_| {
                    format!(
                        "{i} is out of range: a terrain tile is a whole number from 0 to \
                         surface.roughness.tiles - 1"
                    )
                })?);
            }
            Sink::Offset(_, v) => {
                let x = number(cell)?;
                if !x.is_finite() {
                    return Err(format!("{x} is not a finite number"));
                }
                v.push(x);
            }
            Sink::Sample => {
                let i = whole(cell, "sample")?;
                if i != i128::from(row) {
                    return Err(format!(
                        "holds {i}, but the samples are numbered by the table's rows (this \
                         is sample {row}): drop the column, or rename it and pass \
                         --keep-columns to keep it"
                    ));
                }
            }
            Sink::Kept => {}
        }
        Ok(())
    }
}
