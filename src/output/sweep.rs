//! The sweep file: one row per sample (MODEL.md section 9), inputs then results, in sample
//! order, as Arrow IPC or Parquet, written in batches of a fixed row count so that the
//! bytes depend on the scenario and seed alone (not on threads or timing).

use super::format::{BATCH_ROWS, Format};
use super::{AtomicFile, ENGINE, IpcWriter, Out, field};
use crate::scenario::INPUT_FIELDS;
use crate::sweep::{Row, Shard};
use arrow_array::builder::{Float64Builder, StringBuilder, UInt32Builder, UInt64Builder};
use arrow_array::{ArrayRef, RecordBatch};
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use arrow_select::concat::concat_batches;
use parquet::arrow::ArrowWriter;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// Provenance stored in the schema metadata.
pub struct SweepInfo<'a> {
    pub scenario_toml: &'a str,
    pub seed: u64,
    /// Samples of the whole sweep (of all its shards).
    pub samples: u64,
    pub lane_type: &'a str,
    /// The slice of the sweep this file holds, if it is a shard.
    pub shard: Option<Shard>,
    /// The control loop's columns (`CONTROL_COLUMNS`) the file has: none without one.
    pub control: &'a [&'static str],
    /// The columns of the parameters drawn per sample (`PARAMETER_FIELDS`).
    pub parameters: &'a [&'static str],
    /// What the file says of the table of inputs the sweep ran (`scenario::METADATA_KEYS`);
    /// empty without one.
    pub table: &'a [(String, String)],
    /// The table's columns passed through (`--keep-columns`), last.
    pub kept: &'a [arrow_schema::FieldRef],
}

/// The names of the parameter columns (`PARAMETER_FIELDS`) a sweep of `scenario` writes:
/// those it draws per sample.
#[must_use]
pub fn parameter_columns(scenario: &crate::scenario::Scenario) -> Vec<&'static str> {
    crate::scenario::Parameter::ALL
        .iter()
        .filter(|p| scenario.sampled[**p as usize].is_some())
        .map(|p| p.name())
        .collect()
}

/// The columns of what a control loop did, and of its sampled law parameters: name, unit,
/// description, and the law a parameter belongs to (empty: every control loop).
pub const CONTROL_COLUMNS: [(&str, &str, &str, &str); 18] = [
    (
        "propellant_kg",
        "kg",
        "propellant used: thrust integral over Isp g0",
        "",
    ),
    (
        "thrust_on_time_s",
        "s",
        "sum of every thruster's time on",
        "",
    ),
    (
        "firings",
        "1",
        "thruster firings (a thruster on in a control period counts once)",
        "",
    ),
    (
        "hold_down_impulse_n_s",
        "N s",
        "thrust integral of the hold-down firings",
        "",
    ),
    (
        "hold_down_thrust_n",
        "N",
        "sampled law parameter: hold-down thrust",
        "hold_down",
    ),
    (
        "hold_down_duration_s",
        "s",
        "sampled law parameter: hold-down duration",
        "hold_down",
    ),
    (
        "attitude_kp_n_m_per_rad",
        "N m/rad",
        "sampled law parameter: attitude hold proportional gain",
        "attitude_hold",
    ),
    (
        "attitude_kd_n_m_s_per_rad",
        "N m s/rad",
        "sampled law parameter: attitude hold rate gain",
        "attitude_hold",
    ),
    (
        "descent_start_altitude_m",
        "m",
        "sampled law parameter: height of the lowest footpad at the descent's start",
        "descent",
    ),
    (
        "descent_start_speed_m_s",
        "m/s",
        "sampled law parameter: descent speed at the start, down Z_I",
        "descent",
    ),
    (
        "descent_braking_m_s2",
        "m/s^2",
        "sampled law parameter: braking of the descent's profile",
        "descent",
    ),
    (
        "descent_gain_per_s",
        "1/s",
        "sampled law parameter: the descent's approach-rate gain",
        "descent",
    ),
    (
        "descent_release_speed_m_s",
        "m/s",
        "sampled law parameter: approach rate below which the descent releases",
        "descent",
    ),
    (
        "release_time_s",
        "s",
        "when the descent law released the lander (NaN: contact came first)",
        "descent",
    ),
    (
        "release_altitude_m",
        "m",
        "true height of the footpads at release: CG altitude above the surface plane less \
         the footpads' depth below the CG",
        "descent",
    ),
    (
        "release_vx_m_s",
        "m/s",
        "true CG velocity at release, X_I (the residual velocity of the descent)",
        "descent",
    ),
    (
        "release_vy_m_s",
        "m/s",
        "true CG velocity at release, Y_I",
        "descent",
    ),
    (
        "release_vz_m_s",
        "m/s",
        "true CG velocity at release, Z_I",
        "descent",
    ),
];

/// The names of the `CONTROL_COLUMNS` a sweep of `scenario` writes.
#[must_use]
pub fn control_columns(scenario: &crate::scenario::Scenario) -> Vec<&'static str> {
    let Some(c) = &scenario.control else {
        return Vec::new();
    };
    CONTROL_COLUMNS
        .iter()
        .filter(|(_, _, _, law)| match *law {
            "hold_down" => c.hold_down.is_some(),
            "attitude_hold" => c.attitude_hold.is_some(),
            "descent" => c.descent.is_some(),
            _ => true,
        })
        .map(|c| c.0)
        .collect()
}

/// Schema metadata keys of a shard file (a whole sweep has neither).
pub const SHARD_KEYS: [&str; 2] = ["touchdown.shard", "touchdown.sample_range"];

/// The schema of a sweep of a lander with `legs` legs.
#[must_use]
pub fn schema(legs: usize, info: &SweepInfo<'_>) -> SchemaRef {
    let f = |n: &str, t: DataType, u: &str, d: &str| field(n, t, u, d);
    let mut fields: Vec<Field> = vec![
        f("sample", DataType::UInt64, "1", "sample index"),
        f(
            "sample_seed",
            DataType::UInt64,
            "1",
            "seed of the sample's generator",
        ),
    ];
    for (name, unit) in INPUT_FIELDS {
        fields.push(f(name, DataType::Float64, unit, "sampled input"));
    }
    fields.extend([
        f(
            "terrain_tile",
            DataType::UInt32,
            "1",
            "terrain tile (0 on a flat surface)",
        ),
        f(
            "terrain_offset_u_m",
            DataType::Float64,
            "m",
            "landing point offset in the tile, downhill axis",
        ),
        f(
            "terrain_offset_v_m",
            DataType::Float64,
            "m",
            "landing point offset in the tile, cross-slope axis",
        ),
        f(
            "outcome",
            DataType::Utf8,
            "1",
            "stable, tipped, sliding, bouncing or diverged",
        ),
        f(
            "decided_s",
            DataType::Float64,
            "s",
            "time the outcome was decided (t_max for sliding and bouncing)",
        ),
        f("steps", DataType::UInt64, "1", "steps taken"),
        f(
            "final_tilt_deg",
            DataType::Float64,
            "deg",
            "final tilt of Z_B from the slope normal",
        ),
        f(
            "max_tilt_deg",
            DataType::Float64,
            "deg",
            "largest tilt of Z_B from the slope normal",
        ),
        f(
            "displacement_m",
            DataType::Float64,
            "m",
            "distance the CG moved along the surface",
        ),
        f(
            "peak_acceleration_m_s2",
            DataType::Float64,
            "m/s^2",
            "peak contact acceleration of the CG (accelerometer reading)",
        ),
        f(
            "peak_acceleration_z_body_m_s2",
            DataType::Float64,
            "m/s^2",
            "peak contact acceleration along Z_B (instruments' shock)",
        ),
        f(
            "bounces",
            DataType::UInt32,
            "1",
            "lift-offs after the first contact",
        ),
        Field::new("first_contact_s", DataType::Float64, true).with_metadata(
            [
                ("unit", "s"),
                (
                    "description",
                    "time of the first contact (null: never touched)",
                ),
            ]
            .into_iter()
            .collect::<arrow_schema::Metadata>(),
        ),
        f(
            "max_penetration_m",
            DataType::Float64,
            "m",
            "largest footpad penetration",
        ),
    ]);
    for k in 0..legs {
        fields.push(f(
            &format!("leg{k}_peak_normal_force_n"),
            DataType::Float64,
            "N",
            "peak normal force",
        ));
        fields.push(f(
            &format!("leg{k}_stroke_m"),
            DataType::Float64,
            "m",
            "final damper stroke",
        ));
        fields.push(f(
            &format!("leg{k}_absorbed_j"),
            DataType::Float64,
            "J",
            "energy absorbed by the damper",
        ));
    }
    for (name, unit, description, _) in CONTROL_COLUMNS {
        if info.control.contains(&name) {
            let t = if name == "firings" {
                DataType::UInt32
            } else {
                DataType::Float64
            };
            fields.push(f(name, t, unit, description));
        }
    }
    for (name, unit) in crate::scenario::PARAMETER_FIELDS {
        if info.parameters.contains(&name) {
            fields.push(f(
                name,
                DataType::Float64,
                unit,
                "scenario parameter drawn per sample",
            ));
        }
    }
    fields.extend(info.kept.iter().map(|f| f.as_ref().clone()));
    let mut meta = BTreeMap::from([
        ("touchdown.engine".to_string(), ENGINE.to_string()),
        ("touchdown.kind".to_string(), "sweep".to_string()),
        (
            "touchdown.scenario".to_string(),
            info.scenario_toml.to_string(),
        ),
        ("touchdown.seed".to_string(), info.seed.to_string()),
        ("touchdown.samples".to_string(), info.samples.to_string()),
        (
            "touchdown.lane_type".to_string(),
            info.lane_type.to_string(),
        ),
    ]);
    meta.extend(info.table.iter().cloned());
    if let Some(shard) = info.shard {
        let range = shard.range(info.samples);
        meta.insert(SHARD_KEYS[0].to_string(), shard.to_string());
        meta.insert(
            SHARD_KEYS[1].to_string(),
            format!("{}..{}", range.start, range.end),
        );
    }
    Arc::new(Schema::new_with_metadata(fields, meta))
}

/// A record batch of `rows` in `schema`, the columns passed through from a table of
/// inputs (`kept`, last in the schema) as they are.
pub fn batch(
    schema: &SchemaRef,
    legs: usize,
    rows: &[Row],
    kept: Vec<ArrayRef>,
) -> anyhow::Result<RecordBatch> {
    let n = rows.len();
    let u64s = |get: &dyn Fn(&Row) -> u64| {
        let mut b = UInt64Builder::with_capacity(n);
        rows.iter().for_each(|r| b.append_value(get(r)));
        Arc::new(b.finish()) as ArrayRef
    };
    let f64s = |get: &dyn Fn(&Row) -> f64| {
        let mut b = Float64Builder::with_capacity(n);
        rows.iter().for_each(|r| b.append_value(get(r)));
        Arc::new(b.finish()) as ArrayRef
    };
    let u32s = |get: &dyn Fn(&Row) -> u32| {
        let mut b = UInt32Builder::with_capacity(n);
        rows.iter().for_each(|r| b.append_value(get(r)));
        Arc::new(b.finish()) as ArrayRef
    };
    let mut cols: Vec<ArrayRef> = vec![u64s(&|r| r.sample.index), u64s(&|r| r.sample.seed)];
    for k in 0..INPUT_FIELDS.len() {
        cols.push(f64s(&|r| r.sample.inputs.to_array()[k]));
    }
    cols.push(u32s(&|r| r.sample.terrain_tile));
    cols.push(f64s(&|r| r.sample.terrain_offset_m[0]));
    cols.push(f64s(&|r| r.sample.terrain_offset_m[1]));
    let mut outcome = StringBuilder::with_capacity(n, n * 8);
    rows.iter()
        .for_each(|r| outcome.append_value(r.summary.outcome.name()));
    cols.push(Arc::new(outcome.finish()));
    cols.push(f64s(&|r| r.summary.decided_s));
    cols.push(u64s(&|r| r.summary.steps));
    cols.push(f64s(&|r| r.summary.final_tilt_deg));
    cols.push(f64s(&|r| r.summary.max_tilt_deg));
    cols.push(f64s(&|r| r.summary.displacement_m));
    cols.push(f64s(&|r| r.summary.peak_acceleration_m_s2));
    cols.push(f64s(&|r| r.summary.peak_acceleration_z_body_m_s2));
    cols.push(u32s(&|r| r.summary.bounces));
    let mut first = Float64Builder::with_capacity(n);
    rows.iter()
        .for_each(|r| first.append_option(r.summary.first_contact_s));
    cols.push(Arc::new(first.finish()));
    cols.push(f64s(&|r| r.summary.max_penetration_m));
    for k in 0..legs {
        cols.push(f64s(&|r| r.summary.legs[k].peak_normal_force_n));
        cols.push(f64s(&|r| r.summary.legs[k].stroke_m));
        cols.push(f64s(&|r| r.summary.legs[k].absorbed_j));
    }
    let control = |r: &Row| r.summary.control.as_deref().copied().unwrap_or_default();
    let descent = |r: &Row| control(r).descent.unwrap_or_default();
    let computed = schema.fields().len() - kept.len();
    for field in schema.fields()[..computed].iter().skip(cols.len()) {
        cols.push(match field.name().as_str() {
            "propellant_kg" => f64s(&|r| control(r).propellant_kg),
            "thrust_on_time_s" => f64s(&|r| control(r).on_time_s),
            "firings" => u32s(&|r| control(r).firings),
            "hold_down_impulse_n_s" => f64s(&|r| control(r).hold_down_impulse_n_s),
            "hold_down_thrust_n" => f64s(&|r| control(r).hold_down_thrust_n),
            "hold_down_duration_s" => f64s(&|r| control(r).hold_down_duration_s),
            "attitude_kp_n_m_per_rad" => f64s(&|r| control(r).kp_n_m_per_rad),
            "attitude_kd_n_m_s_per_rad" => f64s(&|r| control(r).kd_n_m_s_per_rad),
            "descent_start_altitude_m" => f64s(&|r| descent(r).start_altitude_m),
            "descent_start_speed_m_s" => f64s(&|r| descent(r).start_speed_m_s),
            "descent_braking_m_s2" => f64s(&|r| descent(r).braking_m_s2),
            "descent_gain_per_s" => f64s(&|r| descent(r).gain_per_s),
            "descent_release_speed_m_s" => f64s(&|r| descent(r).release_speed_m_s),
            "release_time_s" => f64s(&|r| control(r).release_time_s),
            "release_altitude_m" => f64s(&|r| control(r).release_altitude_m),
            "release_vx_m_s" => f64s(&|r| control(r).release_velocity_m_s[0]),
            "release_vy_m_s" => f64s(&|r| control(r).release_velocity_m_s[1]),
            "release_vz_m_s" => f64s(&|r| control(r).release_velocity_m_s[2]),
            other => match crate::scenario::Parameter::ALL
                .iter()
                .find(|p| p.name() == other)
            {
                Some(&p) => f64s(&|r| r.sample.parameters[p as usize]),
                None => anyhow::bail!("no column {other} in a sweep"),
            },
        });
    }
    cols.extend(kept);
    Ok(RecordBatch::try_new(schema.clone(), cols)?)
}

enum Writer {
    Arrow(IpcWriter),
    Parquet(ArrowWriter<Out>),
}

/// Writes rows as they come, in batches of `BATCH_ROWS`, to a file that appears under its
/// name only after `finish`.
pub struct SweepWriter {
    path: std::path::PathBuf,
    file: AtomicFile,
    sink: Writer,
    schema: SchemaRef,
    legs: usize,
    pending: Vec<Row>,
    rows: u64,
    /// The table of inputs whose columns pass through (`--keep-columns`).
    table: Option<Arc<crate::scenario::InputTable>>,
}

impl SweepWriter {
    /// Opens the temporary file for `path`.
    pub fn create(
        path: &Path,
        format: Format,
        legs: usize,
        info: &SweepInfo<'_>,
    ) -> anyhow::Result<SweepWriter> {
        let schema = schema(legs, info);
        let (file, out) = AtomicFile::create(path)?;
        let sink = match format {
            Format::Arrow => Writer::Arrow(IpcWriter::new(&file, out, &schema)?),
            Format::Parquet => {
                let props = parquet::file::properties::WriterProperties::builder()
                    .set_compression(parquet::basic::Compression::SNAPPY)
                    .set_max_row_group_row_count(Some(BATCH_ROWS))
                    .set_created_by(ENGINE.to_string())
                    .build();
                Writer::Parquet(ArrowWriter::try_new(out, schema.clone(), Some(props))?)
            }
        };
        Ok(SweepWriter {
            path: path.to_path_buf(),
            file,
            sink,
            schema,
            legs,
            pending: Vec::with_capacity(BATCH_ROWS),
            rows: 0,
            table: None,
        })
    }

    /// Passes the kept columns of `table` (`SweepInfo::kept`) through, row by row.
    #[must_use]
    pub fn with_table(mut self, table: Option<Arc<crate::scenario::InputTable>>) -> SweepWriter {
        self.table = table;
        self
    }

    /// Takes rows in sample order; writes every full batch.
    pub fn push(&mut self, rows: Vec<Row>) -> anyhow::Result<()> {
        for row in rows {
            self.pending.push(row);
            if self.pending.len() == BATCH_ROWS {
                self.flush()?;
            }
        }
        Ok(())
    }

    fn flush(&mut self) -> anyhow::Result<()> {
        if self.pending.is_empty() {
            return Ok(());
        }
        let first = self.pending[0].sample.index;
        debug_assert!(
            self.pending
                .iter()
                .enumerate()
                .all(|(i, r)| r.sample.index == first + i as u64),
            "rows in sample order"
        );
        let kept = match &self.table {
            Some(t) => t.kept_rows(first, self.pending.len())?,
            None => Vec::new(),
        };
        let b = batch(&self.schema, self.legs, &self.pending, kept)?;
        self.pending.clear();
        self.write_batch(&b)
    }

    /// The schema every batch is written in.
    #[must_use]
    pub fn schema(&self) -> &SchemaRef {
        &self.schema
    }

    /// Writes a whole batch as it is (for `merge`, which cuts its batches itself). Not to
    /// be mixed with `push`.
    pub fn write_batch(&mut self, b: &RecordBatch) -> anyhow::Result<()> {
        debug_assert!(self.pending.is_empty(), "write_batch after push");
        let written = match &mut self.sink {
            Writer::Arrow(w) => w.write(b).map_err(|e| e.to_string()),
            Writer::Parquet(w) => w.write(b).map_err(|e| e.to_string()),
        };
        written.map_err(|e| self.write_error(&e))?;
        self.rows += b.num_rows() as u64;
        Ok(())
    }

    /// Writes the last batch, closes the file and gives it its name. Returns the row count.
    pub fn finish(self) -> anyhow::Result<u64> {
        Ok(self.close(None)?.0)
    }

    /// Writes the rows pushed so far and closes the file as a valid one, under the name of
    /// an interrupted sweep (`OUT.interrupted`), not the final name. Returns the row count
    /// and that path; `None` where the output is not a regular file (a device, a FIFO,
    /// standard output): the rows went there, and nothing is made beside it.
    pub fn finish_interrupted(self) -> anyhow::Result<(u64, Option<std::path::PathBuf>)> {
        let path = super::interrupted_path(self.path());
        let (rows, made) = self.close(Some(&path))?;
        Ok((rows, made.then_some(path)))
    }

    /// The path the sweep was asked to write.
    fn path(&self) -> &Path {
        &self.path
    }

    /// An error writing the file, naming it.
    fn write_error(&self, e: &str) -> anyhow::Error {
        anyhow::anyhow!(
            "cannot write output file {}: {e}",
            self.file.partial_path().display()
        )
    }

    /// Writes the last rows and closes the file, renamed onto `name` instead of its final
    /// path if given. Returns the row count, and whether `name` was made.
    fn close(mut self, name: Option<&Path>) -> anyhow::Result<(u64, bool)> {
        self.flush()?;
        let out = match self.sink {
            Writer::Arrow(w) => w.finish().map_err(|e| e.to_string()),
            Writer::Parquet(w) => w.into_inner().map_err(|e| e.to_string()),
        };
        let out = out.map_err(|e| {
            anyhow::anyhow!(
                "cannot write output file {}: {e}",
                self.file.partial_path().display()
            )
        })?;
        let made = match name {
            None => {
                self.file.commit(out)?;
                false
            }
            Some(path) => self.file.commit_as(out, path)?,
        };
        Ok((self.rows, made))
    }
}

/// Cuts a stream of batches into batches of `BATCH_ROWS` rows (the last one shorter), as
/// the sweep writes them, holding at most one batch's rows.
pub struct Rebatcher {
    schema: SchemaRef,
    pieces: Vec<RecordBatch>,
    rows: usize,
}

impl Rebatcher {
    #[must_use]
    pub fn new(schema: SchemaRef) -> Rebatcher {
        Rebatcher {
            schema,
            pieces: Vec::new(),
            rows: 0,
        }
    }

    /// Takes the rows of `b` (columns as in the schema), writing every full batch.
    pub fn push(&mut self, b: RecordBatch, writer: &mut SweepWriter) -> anyhow::Result<()> {
        // The same columns, under the schema of the whole sweep (no shard metadata).
        let mut b = RecordBatch::try_new(self.schema.clone(), b.columns().to_vec())?;
        while self.rows + b.num_rows() >= BATCH_ROWS {
            let take = BATCH_ROWS - self.rows;
            self.pieces.push(b.slice(0, take));
            b = b.slice(take, b.num_rows() - take);
            self.rows = 0;
            self.write(writer)?;
        }
        if b.num_rows() > 0 {
            self.rows += b.num_rows();
            self.pieces.push(b);
        }
        Ok(())
    }

    /// Writes the rows left, if any.
    pub fn finish(mut self, writer: &mut SweepWriter) -> anyhow::Result<()> {
        if self.pieces.is_empty() {
            return Ok(());
        }
        self.write(writer)
    }

    /// Writes the pieces as one batch of fresh (unsliced) arrays.
    fn write(&mut self, writer: &mut SweepWriter) -> anyhow::Result<()> {
        let whole = concat_batches(&self.schema, &self.pieces)?;
        self.pieces.clear();
        writer.write_batch(&whole)
    }
}
