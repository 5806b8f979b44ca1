//! The user's own inputs: `touchdown sweep --inputs TABLE`, a CSV, Arrow (IPC file or
//! stream) or Parquet table with one sample per row.
//!
//! Row `i` is sample `i`. A column named as one of the sweep's input columns gives that
//! sample that value: the 12 inputs, the parameters a scenario may draw (`mass_kg`,
//! `friction_coefficient`, ...), and, to replay rows of a sweep exactly, `sample_seed` (the
//! generator seed that everything else the sample draws comes from: sensor noise, thruster
//! errors, law parameters) and `terrain_tile`, `terrain_offset_u_m`, `terrain_offset_v_m`.
//! Every value the table does not give is drawn from the scenario as for any sweep,
//! seeded by the row index (or by the row's `sample_seed`). A column named as a result of
//! the sweep (`outcome`, ...) is refused; any other column is refused by name, unless
//! `--keep-columns` passes it through to the output unchanged.
//!
//! The whole table is read and checked before any sample runs: a value that is not a
//! number, NaN, infinite, empty or outside what its input allows is refused with its row
//! and column. The file's SHA-256 goes into the sweep's metadata, and `--resume`, `merge`
//! and `trace` hold a sweep to the table it ran. The table is never held whole: its head
//! is read first (a column the sweep has no use for is refused before any row), then its
//! bytes stream through the digest, its cells through the checks, and the sweep reads its
//! rows again, block by block, as it goes.
//!
//! The folder: `read` (a table read and checked, attached to a scenario and reattached to
//! a sweep that ran it), `role` (what each column is to the sweep), `source` (the file's
//! head, and its rows in chunks from any row on: CSV, Arrow or Parquet), `check` (the
//! first pass: every cell checked, what the sweep must know of the whole table), `rows`
//! (the rows as the sweep asks for them, in blocks), `cells` (a cell of any format, and
//! the kept CSV columns), `sink` (where a column's checked values go), `sha256` (the
//! digest a sweep records, and a CSV file's text checked as it streams).

mod cells;
mod check;
mod read;
mod role;
mod rows;
mod sha256;
mod sink;
mod source;

pub use read::{attach, reattach};
pub use sha256::sha256_hex;
