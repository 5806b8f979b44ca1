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
//! and `trace` hold a sweep to the table it ran.

use crate::scenario::{
    Design, Geometry, INPUT_FIELDS, InputTable, METADATA_KEYS, Parameter, Scenario, VALUES,
    check_value, value_name,
};
use anyhow::{anyhow, bail};
use arrow_array::{Array, ArrayRef, RecordBatch, cast::AsArray, types::*};
use arrow_schema::{DataType, Field, FieldRef, Schema};
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl InputTable {
    /// Reads the table at `path` for a sweep of `scenario`, checking every value.
    pub fn read(path: &Path, keep_columns: bool, scenario: &Scenario) -> anyhow::Result<Self> {
        let bytes = std::fs::read(path)
            .map_err(|e| anyhow!("cannot read the input table {}: {e}", path.display()))?;
        let sha256 = sha256_hex(&bytes);
        let source = Source::parse(path, bytes)?;
        let names = source.names();
        let mut roles = Vec::with_capacity(names.len());
        for (j, name) in names.iter().enumerate() {
            if names[..j].contains(name) {
                bail!("{}: column {name} appears twice", path.display());
            }
            roles.push(role(name, keep_columns, scenario, path)?);
        }
        let mut sinks: Vec<Sink> = roles.iter().map(|r| Sink::new(*r)).collect();
        let (rows, kept) = source.fill(&mut sinks, path)?;
        if rows == 0 {
            bail!("{}: the table has no rows", path.display());
        }
        let mut table = InputTable {
            path: path.to_path_buf(),
            format: source.format(),
            sha256,
            rows: rows as u64,
            columns: names.clone(),
            keep_columns,
            values: std::array::from_fn(|_| None),
            sample_seed: None,
            terrain_tile: None,
            terrain_offset_m: [None, None],
            kept,
        };
        for sink in sinks {
            match sink {
                Sink::Value(k, v) => table.values[k] = Some(v),
                Sink::Seed(v) => table.sample_seed = Some(v),
                Sink::Tile(v) => table.terrain_tile = Some(v),
                Sink::Offset(j, v) => table.terrain_offset_m[j] = Some(v),
                Sink::Sample | Sink::Kept => {}
            }
        }
        table.check_terrain(scenario)?;
        Ok(table)
    }

    /// The terrain columns against the surface the sweep will have: a tile the rough
    /// surface has and an offset inside it, or 0 where the surface is flat.
    fn check_terrain(&self, scenario: &Scenario) -> anyhow::Result<()> {
        let rough = &scenario.surface.roughness;
        let k = INPUT_FIELDS.len() + Parameter::RmsHeightM as usize;
        let largest = self.values[k].as_ref().map_or_else(
            || scenario.rms_height_max_m(),
            |c| c.iter().copied().fold(0.0, f64::max),
        );
        let where_ = |row: usize, name: &str, what: String| {
            anyhow!("{}: row {row}, column {name}: {what}", self.path.display())
        };
        if let Some(c) = &self.terrain_tile {
            for (row, &t) in c.iter().enumerate() {
                if largest == 0.0 && t != 0 {
                    return Err(where_(
                        row,
                        "terrain_tile",
                        format!("{t}, but the surface is flat (its only tile is 0)"),
                    ));
                }
                if largest > 0.0 && t as usize >= rough.tiles {
                    return Err(where_(
                        row,
                        "terrain_tile",
                        format!(
                            "{t}, but the surface has tiles 0 to {} (surface.roughness.tiles)",
                            rough.tiles - 1
                        ),
                    ));
                }
            }
        }
        for (j, name) in ["terrain_offset_u_m", "terrain_offset_v_m"]
            .iter()
            .enumerate()
        {
            let Some(c) = &self.terrain_offset_m[j] else {
                continue;
            };
            for (row, &x) in c.iter().enumerate() {
                if largest == 0.0 && x != 0.0 {
                    return Err(where_(
                        row,
                        name,
                        format!("{x}, but the surface is flat (the offset is 0)"),
                    ));
                }
                if largest > 0.0 && !(0.0..rough.tile_size_m).contains(&x) {
                    return Err(where_(
                        row,
                        name,
                        format!(
                            "{x} is outside the tile: values from 0 up to, not including, \
                             {} m (surface.roughness.tile_size_m)",
                            rough.tile_size_m
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Reads the table at `path` and makes `scenario` run it: sample `i` takes row `i`'s
/// values. A parameter the table gives becomes one the scenario draws per sample, over
/// the range of the table's values joined to the scenario's own distribution's if it has
/// one (the terrain is built for the largest roughness of that range, early sliding decided
/// at its worst corner), so that a table of a sweep's own draws runs as that sweep did.
pub fn attach(scenario: &mut Scenario, path: &Path, keep_columns: bool) -> anyhow::Result<()> {
    if scenario.design == Design::SobolIndices {
        bail!(
            "--inputs {}: the scenario's design is \"sobol-indices\", whose samples come in \
             blocks made from each other; a table gives each sample its own row (use design \
             \"independent\" or \"sobol-sequence\")",
            path.display()
        );
    }
    let table = InputTable::read(path, keep_columns, scenario)?;
    for p in Parameter::ALL {
        let k = INPUT_FIELDS.len() + p as usize;
        if let Some(c) = &table.values[k] {
            let (min, max) = c
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            // Where the scenario draws it already and the table stays within its
            // distribution's range, the distribution stays: nothing that depends on it
            // changes (the tiles' roughness, the worst corner, a grid's digits), and the
            // table's values run as the scenario's own.
            scenario.sampled[p as usize] = match scenario.sampled[p as usize] {
                Some(d) if d.support().0 <= min && max <= d.support().1 => Some(d),
                Some(d) => Some(crate::scenario::Dist::Uniform {
                    min: d.support().0.min(min),
                    max: d.support().1.max(max),
                }),
                None => Some(crate::scenario::Dist::Uniform { min, max }),
            };
        }
    }
    scenario.table = Some(Arc::new(table));
    Ok(())
}

/// Gives `scenario` the table of inputs that the run whose file `file` has metadata
/// `meta` ran with, if any: the table at `given` (the command line's `--inputs`) or where
/// the metadata says it was, holding it to the same bytes (SHA-256) and way of reading.
pub fn reattach(
    scenario: &mut Scenario,
    meta: &arrow_schema::Metadata,
    given: Option<&Path>,
    file: &Path,
) -> anyhow::Result<()> {
    let Some(sha256) = meta.get(METADATA_KEYS[1]) else {
        if let Some(path) = given {
            bail!(
                "--inputs {}: {} did not run a table of inputs",
                path.display(),
                file.display()
            );
        }
        return Ok(());
    };
    let stored = meta.get(METADATA_KEYS[0]).map_or("", String::as_str);
    let path = given.map_or_else(|| PathBuf::from(stored), Path::to_path_buf);
    if given.is_none() && !path.exists() {
        bail!(
            "{} ran the table of inputs {stored}, which is not there: give it with --inputs \
             (its SHA-256 is {sha256})",
            file.display()
        );
    }
    let keep = meta.get(METADATA_KEYS[4]).is_some_and(|v| v == "true");
    attach(scenario, &path, keep)?;
    let table = scenario.table.as_ref().expect("attached");
    if &table.sha256 != sha256 {
        bail!(
            "{} is not the table of inputs {} ran: its SHA-256 is {}, the sweep's {sha256}",
            path.display(),
            file.display(),
            table.sha256
        );
    }
    Ok(())
}

/// What a column of the table is to the sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    /// Value `k` of a sample (`Sample::values`).
    Value(usize),
    Seed,
    Tile,
    /// Terrain offset, downhill (0) or cross-slope (1).
    Offset(usize),
    /// The sample index: it must be the row's.
    Sample,
    /// Passed through to the output.
    Kept,
}

/// The role of column `name` in a sweep of `scenario`; refuses a result column, a
/// parameter the scenario cannot take per sample, and (without `keep`) an unknown column.
fn role(name: &str, keep: bool, scenario: &Scenario, path: &Path) -> anyhow::Result<Role> {
    if let Some(k) = (0..VALUES).find(|&k| value_name(k) == name) {
        if k >= INPUT_FIELDS.len() {
            let p = Parameter::ALL[k - INPUT_FIELDS.len()];
            let refuse =
                |why: &str| anyhow!("{}: column {name} ({}): {why}", path.display(), p.key());
            match p {
                Parameter::CrushStrengthPsi if !scenario.damper.enabled => {
                    return Err(refuse(
                        "the scenario has damper.enabled = false, no cartridge to crush",
                    ));
                }
                Parameter::CrushStrengthPsi if scenario.damper.stages.len() > 1 => {
                    return Err(refuse(
                        "the scenario's damper has several stages (damper.stages): one crush \
                         strength per sample is for a single-stage cartridge",
                    ));
                }
                Parameter::MassKg | Parameter::CgHeightM if scenario.control.is_some() => {
                    return Err(refuse(
                        "not drawn per sample in a scenario with a control loop (its thrust \
                         limits and descent are planned for one lander)",
                    ));
                }
                Parameter::CgHeightM if matches!(scenario.lander.geometry, Geometry::Tips(_)) => {
                    return Err(refuse(
                        "the scenario places the footpads by lander.leg_tips_m, not by a CG \
                         height",
                    ));
                }
                _ => {}
            }
        }
        return Ok(Role::Value(k));
    }
    match name {
        "sample_seed" => return Ok(Role::Seed),
        "terrain_tile" => return Ok(Role::Tile),
        "terrain_offset_u_m" => return Ok(Role::Offset(0)),
        "terrain_offset_v_m" => return Ok(Role::Offset(1)),
        "sample" => return Ok(Role::Sample),
        _ => {}
    }
    if is_result_column(name) {
        bail!(
            "{}: column {name} is a result of a sweep, not one of its inputs: give the \
             input columns alone (or rename it to keep it with --keep-columns)",
            path.display()
        );
    }
    if keep {
        return Ok(Role::Kept);
    }
    bail!(
        "{}: unknown column {name}: the sweep's input columns are sample_seed, {}, \
         terrain_tile, terrain_offset_u_m and terrain_offset_v_m; --keep-columns passes other \
         columns through to the output",
        path.display(),
        (0..VALUES).map(value_name).collect::<Vec<_>>().join(", ")
    )
}

/// Whether `name` is a column that a sweep writes as a result (of any lander, with any
/// control loop); `sample` and `sample_seed` have roles of their own (`role`).
fn is_result_column(name: &str) -> bool {
    const RESULTS: [&str; 11] = [
        "outcome",
        "decided_s",
        "steps",
        "final_tilt_deg",
        "max_tilt_deg",
        "displacement_m",
        "peak_acceleration_m_s2",
        "peak_acceleration_z_body_m_s2",
        "bounces",
        "first_contact_s",
        "max_penetration_m",
    ];
    let leg = name.strip_prefix("leg").is_some_and(|rest| {
        let digits = rest.chars().take_while(char::is_ascii_digit).count();
        digits > 0
            && ["_peak_normal_force_n", "_stroke_m", "_absorbed_j"].contains(&&rest[digits..])
    });
    RESULTS.contains(&name)
        || leg
        || crate::output::sweep::CONTROL_COLUMNS
            .iter()
            .any(|c| c.0 == name)
}

/// A cell of the table: a whole number, a floating-point one, or text (or nothing).
enum Cell<'a> {
    Int(i128),
    Float(f64),
    Text(&'a str),
    Null,
}

/// Where a column's checked values go.
enum Sink {
    Value(usize, Vec<f64>),
    Seed(Vec<u64>),
    Tile(Vec<u32>),
    Offset(usize, Vec<f64>),
    Sample,
    Kept,
}

impl Sink {
    fn new(role: Role) -> Sink {
        match role {
            Role::Value(k) => Sink::Value(k, Vec::new()),
            Role::Seed => Sink::Seed(Vec::new()),
            Role::Tile => Sink::Tile(Vec::new()),
            Role::Offset(j) => Sink::Offset(j, Vec::new()),
            Role::Sample => Sink::Sample,
            Role::Kept => Sink::Kept,
        }
    }

    fn is_kept(&self) -> bool {
        matches!(self, Sink::Kept)
    }

    /// Takes the cell of row `row`; what is wrong with it, if anything.
    fn take(&mut self, row: usize, cell: Cell<'_>) -> Result<(), String> {
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
                Cell::Float(x) if x.fract() == 0.0 && x.abs() < 2f64.powi(53) && what != "seed" => {
                    Ok(x as i128)
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
                v.push(u32::try_from(i).map_err(|_| format!("{i} is not a tile number"))?);
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
                if i != row as i128 {
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

/// The table as read from its file.
enum Source {
    /// Its header read; its records are read as they are checked (`fill`).
    Csv { header: Vec<String>, text: Vec<u8> },
    Arrow {
        format: &'static str,
        columns: Vec<(FieldRef, ArrayRef)>,
        rows: usize,
    },
}

impl Source {
    /// Tells the format from the first bytes: Parquet (`PAR1`), an Arrow IPC file
    /// (`ARROW1`) or stream (a continuation marker), else CSV.
    fn parse(path: &Path, bytes: Vec<u8>) -> anyhow::Result<Source> {
        let context = |e: &dyn std::fmt::Display| {
            let text = e.to_string();
            match text.split("Disabled feature at compile time: ").nth(1) {
                Some(codec) => anyhow!(
                    "cannot read {}: it is compressed with {}, which touchdown does not read \
                     (Parquet: snappy, zstd, gzip, lz4 or none; Arrow: lz4, zstd or none)",
                    path.display(),
                    codec.trim()
                ),
                None => anyhow!("cannot read {}: {text}", path.display()),
            }
        };
        let batches: (Vec<RecordBatch>, Arc<Schema>, &'static str) = if bytes.starts_with(b"PAR1") {
            let b = parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder::try_new(
                bytes::Bytes::from(bytes),
            )
            .map_err(|e| context(&e))?;
            let schema = b.schema().clone();
            let r = b.build().map_err(|e| context(&e))?;
            let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
            (batches, schema, "parquet")
        } else if bytes.starts_with(b"ARROW1") {
            let r = arrow_ipc::reader::FileReader::try_new(std::io::Cursor::new(bytes), None)
                .map_err(|e| context(&e))?;
            let schema = r.schema();
            let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
            (batches, schema, "arrow")
        } else if bytes.starts_with(&[0xff, 0xff, 0xff, 0xff]) {
            let r = arrow_ipc::reader::StreamReader::try_new(std::io::Cursor::new(bytes), None)
                .map_err(|e| context(&e))?;
            let schema = r.schema();
            let batches = r.collect::<Result<Vec<_>, _>>().map_err(|e| context(&e))?;
            (batches, schema, "arrow")
        } else {
            return Source::csv(path, bytes);
        };
        let (batches, schema, format) = batches;
        let rows = batches.iter().map(RecordBatch::num_rows).sum();
        let columns = schema
            .fields()
            .iter()
            .enumerate()
            .map(|(j, f)| {
                let pieces: Vec<&dyn Array> =
                    batches.iter().map(|b| b.column(j).as_ref()).collect();
                let whole = if pieces.is_empty() {
                    arrow_array::new_empty_array(f.data_type())
                } else {
                    arrow_select::concat::concat(&pieces).map_err(|e| context(&e))?
                };
                Ok((f.clone(), whole))
            })
            .collect::<anyhow::Result<_>>()?;
        Ok(Source::Arrow {
            format,
            columns,
            rows,
        })
    }

    fn csv(path: &Path, bytes: Vec<u8>) -> anyhow::Result<Source> {
        if let Err(e) = std::str::from_utf8(&bytes) {
            bail!(
                "{} is neither Parquet, Arrow nor CSV text (not UTF-8 at byte {})",
                path.display(),
                e.valid_up_to()
            );
        }
        let header: Vec<String> = csv_reader(&bytes)
            .headers()
            .map_err(|e| anyhow!("{}: {e}", path.display()))?
            .iter()
            .map(str::to_string)
            .collect();
        if header.iter().all(String::is_empty) {
            bail!("{}: no header row naming the columns", path.display());
        }
        if let Some(j) = header.iter().position(String::is_empty) {
            bail!(
                "{}: column {} has no name in the header",
                path.display(),
                j + 1
            );
        }
        // The CSV reader skips blank lines, which in a one-column table are empty values:
        // refuse one before the last row (outside a quoted field: after an even number of
        // quotes), as it would shift every later row's sample.
        let text = std::str::from_utf8(&bytes).unwrap_or_default();
        let lines: Vec<&str> = text.lines().collect();
        let last = lines
            .iter()
            .rposition(|l| !l.trim().is_empty())
            .unwrap_or(0);
        let mut quotes = 0;
        for (i, l) in lines[..last].iter().enumerate() {
            if i > 0 && quotes % 2 == 0 && l.trim().is_empty() {
                bail!(
                    "{}: line {} is blank: every row needs its values (a blank line would \
                     shift every later row's sample)",
                    path.display(),
                    i + 1
                );
            }
            quotes += l.matches('"').count();
        }
        Ok(Source::Csv {
            header,
            text: bytes,
        })
    }

    fn format(&self) -> &'static str {
        match self {
            Source::Csv { .. } => "csv",
            Source::Arrow { format, .. } => format,
        }
    }

    fn names(&self) -> Vec<String> {
        match self {
            Source::Csv { header, .. } => header.clone(),
            Source::Arrow { columns, .. } => {
                columns.iter().map(|(f, _)| f.name().clone()).collect()
            }
        }
    }

    /// Feeds every cell to its column's sink; gives the number of rows, and the kept
    /// columns as one batch.
    fn fill(
        &self,
        sinks: &mut [Sink],
        path: &Path,
    ) -> anyhow::Result<(usize, Option<RecordBatch>)> {
        let names = self.names();
        let mut kept: Vec<(FieldRef, ArrayRef)> = Vec::new();
        let rows = match self {
            Source::Csv { text, .. } => {
                let mut reader = csv_reader(text);
                let mut record = csv::StringRecord::new();
                let mut texts: Vec<Vec<String>> = vec![Vec::new(); sinks.len()];
                let mut row = 0;
                while reader
                    .read_record(&mut record)
                    .map_err(|e| csv_error(&e, path))?
                {
                    let line = record.position().map_or(0, csv::Position::line);
                    for (j, sink) in sinks.iter_mut().enumerate() {
                        if sink.is_kept() {
                            texts[j].push(record[j].to_string());
                            continue;
                        }
                        sink.take(row, csv_cell(&record[j])).map_err(|why| {
                            anyhow!(
                                "{}: row {row} (line {line}), column {}: {why}",
                                path.display(),
                                names[j]
                            )
                        })?;
                    }
                    row += 1;
                }
                for (j, sink) in sinks.iter().enumerate() {
                    if sink.is_kept() {
                        let array = csv_array(texts[j].iter().map(String::as_str));
                        let field = Field::new(&names[j], array.data_type().clone(), true);
                        kept.push((Arc::new(field), array));
                    }
                }
                row
            }
            Source::Arrow { columns, rows, .. } => {
                for ((field, array), sink) in columns.iter().zip(sinks.iter_mut()) {
                    if sink.is_kept() {
                        kept.push((field.clone(), array.clone()));
                        continue;
                    }
                    let fail = |row: usize, why: String| {
                        anyhow!(
                            "{}: row {row}, column {}: {why}",
                            path.display(),
                            field.name()
                        )
                    };
                    arrow_cells(array, &mut |row, cell| {
                        sink.take(row, cell).map_err(|why| fail(row, why))
                    })
                    .map_err(|e| match e {
                        CellError::Type(t) => anyhow!(
                            "{}: column {} is of type {t}: its values must be numbers",
                            path.display(),
                            field.name()
                        ),
                        CellError::At(e) => e,
                    })?;
                }
                *rows
            }
        };
        if kept.is_empty() {
            return Ok((rows, None));
        }
        let (fields, arrays): (Vec<FieldRef>, Vec<ArrayRef>) = kept.into_iter().unzip();
        let batch = RecordBatch::try_new(Arc::new(Schema::new(fields)), arrays)?;
        Ok((rows, Some(batch)))
    }
}

/// A reader of CSV text with a header row, fields trimmed.
fn csv_reader(text: &[u8]) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .from_reader(text)
}

/// An error of the CSV reader, with its line where it has one.
fn csv_error(e: &csv::Error, path: &Path) -> anyhow::Error {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            pos: Some(pos),
            expected_len,
            len,
        } => anyhow!(
            "{}: line {} has {len} fields, the header {expected_len}",
            path.display(),
            pos.line()
        ),
        _ => anyhow!("{}: {e}", path.display()),
    }
}

/// A CSV field as a cell: a whole number, a number, nothing (empty) or text.
fn csv_cell(text: &str) -> Cell<'_> {
    if text.is_empty() {
        Cell::Null
    } else if let Ok(i) = text.parse::<i128>() {
        Cell::Int(i)
    } else if let Ok(x) = text.parse::<f64>() {
        Cell::Float(x)
    } else {
        Cell::Text(text)
    }
}

/// A kept CSV column as an Arrow array: 64-bit integers if every field is one, else
/// floating-point numbers if every field is one, else text; empty fields are null.
fn csv_array<'a>(fields: impl Iterator<Item = &'a str> + Clone) -> ArrayRef {
    let cells = || fields.clone().filter(|t| !t.is_empty());
    let opt = |t: &'a str| (!t.is_empty()).then_some(t);
    if cells().all(|t| t.parse::<i64>().is_ok()) {
        Arc::new(arrow_array::Int64Array::from_iter(
            fields.map(|t| opt(t).map(|t| t.parse::<i64>().expect("checked"))),
        ))
    } else if cells().all(|t| t.parse::<f64>().is_ok()) {
        Arc::new(arrow_array::Float64Array::from_iter(
            fields.map(|t| opt(t).map(|t| t.parse::<f64>().expect("checked"))),
        ))
    } else {
        Arc::new(arrow_array::StringArray::from_iter(fields.map(opt)))
    }
}

enum CellError {
    /// The column's type holds no numbers.
    Type(DataType),
    At(anyhow::Error),
}

/// Calls `f` on every cell of a numeric (or text) Arrow column, in row order.
fn arrow_cells(
    a: &ArrayRef,
    f: &mut dyn FnMut(usize, Cell<'_>) -> anyhow::Result<()>,
) -> Result<(), CellError> {
    macro_rules! each {
        ($t:ty, $wrap:expr) => {{
            let p = a.as_primitive::<$t>();
            for row in 0..p.len() {
                let cell = if p.is_null(row) {
                    Cell::Null
                } else {
                    $wrap(p.value(row))
                };
                f(row, cell).map_err(CellError::At)?;
            }
        }};
    }
    match a.data_type() {
        DataType::Float64 => each!(Float64Type, Cell::Float),
        DataType::Float32 => each!(Float32Type, |x: f32| Cell::Float(f64::from(x))),
        DataType::Int64 => each!(Int64Type, |x| Cell::Int(i128::from(x))),
        DataType::Int32 => each!(Int32Type, |x| Cell::Int(i128::from(x))),
        DataType::Int16 => each!(Int16Type, |x| Cell::Int(i128::from(x))),
        DataType::Int8 => each!(Int8Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt64 => each!(UInt64Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt32 => each!(UInt32Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt16 => each!(UInt16Type, |x| Cell::Int(i128::from(x))),
        DataType::UInt8 => each!(UInt8Type, |x| Cell::Int(i128::from(x))),
        DataType::Utf8 | DataType::LargeUtf8 | DataType::Utf8View => {
            let texts: Vec<Option<&str>> = match a.data_type() {
                DataType::Utf8 => a.as_string::<i32>().iter().collect(),
                DataType::LargeUtf8 => a.as_string::<i64>().iter().collect(),
                _ => a.as_string_view().iter().collect(),
            };
            for (row, t) in texts.into_iter().enumerate() {
                // Numbers written as text read as in a CSV file.
                let cell = t.map_or(Cell::Null, csv_cell);
                f(row, cell).map_err(CellError::At)?;
            }
        }
        t => return Err(CellError::Type(t.clone())),
    }
    Ok(())
}

/// SHA-256 of `bytes`, in lower-case hexadecimal.
#[must_use]
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest;
    sha2::Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_of_known_texts() {
        // FIPS 180-2 test vectors.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
    }

    #[test]
    fn csv_columns_keep_their_type() {
        let ints = csv_array(["1", "", "-3"].into_iter());
        assert_eq!(ints.data_type(), &DataType::Int64);
        assert_eq!(ints.null_count(), 1);
        let floats = csv_array(["1", "2.5"].into_iter());
        assert_eq!(floats.data_type(), &DataType::Float64);
        let text = csv_array(["1", "a"].into_iter());
        assert_eq!(text.data_type(), &DataType::Utf8);
    }

    #[test]
    fn result_columns_are_told_from_inputs() {
        for name in [
            "outcome",
            "leg3_stroke_m",
            "leg12_absorbed_j",
            "propellant_kg",
        ] {
            assert!(is_result_column(name), "{name}");
        }
        for name in ["slope_deg", "leg_count", "legs_stroke_m", "my_column"] {
            assert!(!is_result_column(name), "{name}");
        }
    }
}
