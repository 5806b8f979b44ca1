//! The time history of one sample (MODEL.md section 9): one row per step, or per
//! `every` steps, as an Arrow IPC file written batch by batch.
//!
//! A scenario with a control loop adds its columns after the legs' (`control_columns`):
//! every thruster's thrust and commanded on-time, the thrust on the lander, the loop's
//! phase, and what its sensors read beside the true state.

use super::{AtomicFile, ENGINE, IpcWriter, cannot_write, field};
use crate::control::ControlModel;
use crate::reference::{Model, StepReport, Summary};
use crate::scenario::Sample;
use crate::slope::Surface;
use arrow_array::{ArrayRef, Float64Array, RecordBatch, StringArray};
use arrow_schema::{DataType, Schema};
use glam::{DMat3, DQuat, DVec3, EulerRot};
use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::Path;
use std::sync::Arc;

mod columns;

pub use columns::PHASE_COLUMN;
use columns::{columns, control_columns};

/// Rows per record batch.
const BATCH_ROWS: usize = 8192;

/// The columns of one trace being filled, a batch at a time, in the order of the schema:
/// the numbers of every row, then (with a control loop) the phase and the sensed values.
struct Rows {
    numbers: Vec<Vec<f64>>,
    phase: Vec<&'static str>,
    sensed: Vec<Vec<Option<f64>>>,
    /// A row's numbers and sensed values on their way.
    buf: Vec<f64>,
    sensed_buf: Vec<Option<f64>>,
}

impl Rows {
    fn new(numbers: usize, sensed: usize) -> Rows {
        Rows {
            numbers: vec![Vec::with_capacity(BATCH_ROWS); numbers],
            phase: Vec::new(),
            sensed: vec![Vec::new(); sensed],
            buf: Vec::with_capacity(numbers),
            sensed_buf: Vec::with_capacity(sensed),
        }
    }

    fn len(&self) -> usize {
        self.numbers[0].len()
    }

    /// Appends the row of `r`; `loop_` is the control loop's part, and the propellant used
    /// before the step.
    fn push(&mut self, model: &Model, r: &StepReport, loop_: Option<(&Looped, f64)>) {
        row(model, r, &mut self.buf);
        if let Some((l, propellant_kg)) = loop_ {
            let phase = l.row(r, propellant_kg, &mut self.buf, &mut self.sensed_buf);
            self.phase.push(phase);
            for (c, v) in self.sensed.iter_mut().zip(&self.sensed_buf) {
                c.push(*v);
            }
        }
        for (c, v) in self.numbers.iter_mut().zip(&self.buf) {
            c.push(*v);
        }
    }

    /// The rows so far as a batch of `schema`; empties the columns.
    fn take(&mut self, schema: &Arc<Schema>, control: bool) -> anyhow::Result<RecordBatch> {
        let mut arrays: Vec<ArrayRef> = self
            .numbers
            .iter_mut()
            .map(|c| Arc::new(Float64Array::from(std::mem::take(c))) as ArrayRef)
            .collect();
        if control {
            arrays.push(Arc::new(StringArray::from(std::mem::take(&mut self.phase))));
            arrays.extend(
                self.sensed
                    .iter_mut()
                    .map(|c| Arc::new(Float64Array::from(std::mem::take(c))) as ArrayRef),
            );
        }
        Ok(RecordBatch::try_new(schema.clone(), arrays)?)
    }
}

/// One row of the trace from a step report.
fn row(model: &Model, r: &StepReport, out: &mut Vec<f64>) {
    out.clear();
    let b = &r.body;
    // The specific force per unit mass (contact and thrust): dv/dt less gravity.
    let acc = r.specific_force_n() / model.mass_kg;
    let z_body = DMat3::from_quat(b.attitude).z_axis;
    let (yaw, pitch, roll) = b.attitude.to_euler(EulerRot::ZYX);
    let rate = b.rate_rad_s * (1.0f64).to_degrees();
    out.extend_from_slice(&[
        r.t_s,
        r.dt_s,
        b.position_m.x,
        b.position_m.y,
        b.position_m.z,
        b.velocity_m_s.x,
        b.velocity_m_s.y,
        b.velocity_m_s.z,
        acc.x,
        acc.y,
        acc.z - model.gravity_m_s2,
        acc.dot(z_body),
        b.attitude.w,
        b.attitude.x,
        b.attitude.y,
        b.attitude.z,
        roll.to_degrees(),
        pitch.to_degrees(),
        yaw.to_degrees(),
        rate.x,
        rate.y,
        rate.z,
    ]);
    for &i in &model.leg_index {
        let l = &r.legs[i];
        out.extend_from_slice(&[
            l.tip_m.x,
            l.tip_m.y,
            l.tip_m.z,
            l.penetration_m,
            l.normal_n,
            l.friction_n,
            l.stroke_m,
            l.axial_force_n,
            l.side_force_n,
        ]);
    }
}

/// The angle between Z_B and Z_I of `attitude`, deg.
fn tilt_deg(attitude: DQuat) -> f64 {
    let z = attitude * DVec3::Z;
    libm::atan2(z.x.hypot(z.y), z.z).to_degrees()
}

/// What the control loop's columns of a row need: the loop, and the surface normal its
/// altimeter measures along.
struct Looped<'a> {
    control: &'a ControlModel,
    normal: DVec3,
}

impl Looped<'_> {
    /// Appends the control loop's numbers of the row of `r` to `numbers`, writes its sensed
    /// values to `sensed`; returns its phase.
    fn row(
        &self,
        r: &StepReport,
        propellant_kg: f64,
        numbers: &mut Vec<f64>,
        sensed: &mut Vec<Option<f64>>,
    ) -> &'static str {
        let c = r.control.as_ref();
        for j in 0..self.control.thrusters.len() {
            let at = |v: Option<&Vec<f64>>| v.and_then(|v| v.get(j)).copied().unwrap_or(0.0);
            numbers.push(at(c.map(|c| &c.thrust_n)));
            numbers.push(at(c.map(|c| &c.commanded_on_s)));
        }
        let (f, m) = (r.thrust.force_b_n, r.thrust.moment_b_n_m);
        let b = &r.body;
        numbers.extend_from_slice(&[
            f.x,
            f.y,
            f.z,
            m.x,
            m.y,
            m.z,
            r.thrust.flow_n,
            propellant_kg,
            self.normal.dot(b.position_m),
            tilt_deg(b.attitude),
        ]);
        sensed.clear();
        match c.and_then(|c| c.sensed) {
            Some(s) => {
                let (yaw, pitch, roll) = s.attitude.to_euler(EulerRot::ZYX);
                let rate = s.rate_rad_s * (1.0f64).to_degrees();
                let v = s.velocity_m_s;
                sensed.extend(
                    [
                        s.t_s,
                        roll.to_degrees(),
                        pitch.to_degrees(),
                        yaw.to_degrees(),
                        tilt_deg(s.attitude),
                        rate.x,
                        rate.y,
                        rate.z,
                        v.x,
                        v.y,
                        v.z,
                        s.altitude_m,
                    ]
                    .map(Some),
                );
            }
            None => sensed.resize(SENSED_COLUMNS, None),
        }
        c.map_or("", |c| c.phase)
    }
}

/// The number of sensed columns (`control_columns`).
const SENSED_COLUMNS: usize = 12;

/// Provenance and results stored in the schema metadata of a trace.
pub struct TraceInfo<'a> {
    /// The scenario's TOML text.
    pub scenario_toml: &'a str,
    /// The seed of the sweep the sample belongs to (the scenario's seed).
    pub sweep_seed: u64,
    /// The sample run: its drawn inputs.
    pub sample: &'a Sample,
    /// The sample's results from the reference model.
    pub summary: &'a Summary,
    /// The table of inputs the sample's row came from, if any.
    pub table: Option<&'a crate::scenario::InputTable>,
    /// The control columns a sweep of the scenario writes (`sweep::control_columns`): what
    /// flew, whose values the metadata stores (`control_values`).
    pub control: &'a [&'static str],
}

/// The values of the control columns `names` (`CONTROL_COLUMNS`) in `summary`, as a sweep
/// row has them: name, unit and value (none without a control loop).
#[must_use]
pub fn control_values(
    names: &[&'static str],
    summary: &Summary,
) -> Vec<(&'static str, &'static str, f64)> {
    let Some(c) = summary.control.as_deref() else {
        return Vec::new();
    };
    super::sweep::CONTROL_COLUMNS
        .iter()
        .filter(|(name, ..)| names.contains(name))
        .filter_map(|&(name, unit, ..)| {
            super::sweep::control_value(name).map(|value| (name, unit, value(c)))
        })
        .collect()
}

/// Runs `sample` with the reference model and writes every `every`-th step to `path`, the
/// state at the start of each, and last the state at the decision. Returns the number of
/// rows written.
pub fn write(path: &Path, model: &Model, info: &TraceInfo<'_>, every: u64) -> anyhow::Result<u64> {
    let (file, out) = AtomicFile::create(path)?;
    let mut out = Some(out);
    let mut writer: Option<IpcWriter> = None;
    let rows = record(model, info, every, |b| {
        let w = match (&mut writer, out.take()) {
            (Some(w), _) => w,
            (None, Some(out)) => writer.insert(
                IpcWriter::new(&file, out, &b.schema()).map_err(|e| cannot_write(path, e))?,
            ),
            (None, None) => unreachable!("the output is taken by the first batch only"),
        };
        w.write(b).map_err(|e| cannot_write(path, e))
    })?;
    let writer = writer.expect("a trace has at least its last row");
    let mut out = writer.finish().map_err(|e| cannot_write(path, e))?;
    out.flush().map_err(|e| cannot_write(path, e))?;
    file.commit(out)?;
    Ok(rows)
}

/// The time history `write` writes, as batches in memory (all of one schema, with the
/// trace's metadata).
pub fn batches(
    model: &Model,
    info: &TraceInfo<'_>,
    every: u64,
) -> anyhow::Result<Vec<RecordBatch>> {
    let mut batches = Vec::new();
    record(model, info, every, |b| {
        batches.push(b.clone());
        Ok(())
    })?;
    Ok(batches)
}

/// Runs `sample` with the reference model and hands every `every`-th step, the state at the
/// start of each, and last the state at the decision, to `sink` in batches of at most
/// `BATCH_ROWS` rows. Returns the number of rows.
fn record(
    model: &Model,
    info: &TraceInfo<'_>,
    every: u64,
    mut sink: impl FnMut(&RecordBatch) -> anyhow::Result<()>,
) -> anyhow::Result<u64> {
    let mut fields: Vec<_> = columns(model.legs.len(), model.control.is_some())
        .iter()
        .map(|(n, u, d)| field(n, DataType::Float64, u, d))
        .collect();
    let looped = model.control.as_ref().map(|control| Looped {
        control,
        normal: Surface::of(info.sample).normal,
    });
    let (mut numbers, mut sensed) = (fields.len(), 0);
    if let Some(l) = &looped {
        let (more, read) = control_columns(l.control.thrusters.len());
        debug_assert_eq!(read.len(), SENSED_COLUMNS);
        numbers += more.len();
        sensed = read.len();
        fields.extend(
            more.iter()
                .map(|(n, u, d)| field(n, DataType::Float64, u, d)),
        );
        fields.push(field(
            PHASE_COLUMN,
            DataType::Utf8,
            "1",
            "phase of the control loop during the step: descent, fall, hold_down, user (a \
             law of the user's own) or done",
        ));
        fields.extend(
            read.iter()
                .map(|(n, u, d)| field(n, DataType::Float64, u, d).with_nullable(true)),
        );
    }
    let meta = metadata(info, every);
    let schema = Arc::new(Schema::new_with_metadata(fields, meta));

    let mut data = Rows::new(numbers, sensed);
    let control = looped.is_some();
    let mut rows = 0u64;
    let mut index = 0u64;
    // Thrust integral so far, N s.
    let mut impulse_n_s = 0.0;
    let propellant = |impulse_n_s: f64| {
        looped
            .as_ref()
            .map(|l| (l, impulse_n_s / l.control.exhaust_speed_m_s))
    };
    let mut failure: Option<anyhow::Error> = None;
    let (_, end) = crate::reference::run::run_to_end(model, info.sample, |report| {
        if failure.is_some() {
            return;
        }
        if index.is_multiple_of(every) {
            data.push(model, report, propellant(impulse_n_s));
            rows += 1;
            if data.len() >= BATCH_ROWS
                && let Err(e) = data.take(&schema, control).and_then(|b| sink(&b))
            {
                failure = Some(e);
            }
        }
        impulse_n_s += report.thrust.flow_n * report.dt_s;
        index += 1;
    });
    if let Some(e) = failure {
        return Err(e);
    }
    // The last row is the state at the decision, whatever `every`.
    data.push(model, &end, propellant(impulse_n_s));
    rows += 1;
    if data.len() > 0 {
        sink(&data.take(&schema, control)?)?;
    }
    Ok(rows)
}

/// The trace's provenance: engine, kind, scenario, seeds, the sample (index, outcome,
/// terrain, inputs, parameters) and its table of inputs, `every`, and with a control loop
/// what flew (`touchdown.control.NAME`: its law parameters, propellant and release state,
/// as the sweep's columns of that name).
fn metadata(info: &TraceInfo<'_>, every: u64) -> BTreeMap<String, String> {
    let s = info.summary;
    let mut meta = BTreeMap::from([
        ("touchdown.engine".to_string(), ENGINE.to_string()),
        ("touchdown.kind".to_string(), "trace".to_string()),
        (
            "touchdown.scenario".to_string(),
            info.scenario_toml.to_string(),
        ),
        ("touchdown.seed".to_string(), info.sweep_seed.to_string()),
        (
            "touchdown.sample".to_string(),
            info.sample.index.to_string(),
        ),
        (
            "touchdown.sample_seed".to_string(),
            info.sample.seed.to_string(),
        ),
        (
            "touchdown.outcome".to_string(),
            s.outcome.name().to_string(),
        ),
        ("touchdown.decided_s".to_string(), s.decided_s.to_string()),
        ("touchdown.every".to_string(), every.to_string()),
        (
            "touchdown.terrain_tile".to_string(),
            info.sample.terrain_tile.to_string(),
        ),
        (
            "touchdown.terrain_offset_u_m".to_string(),
            info.sample.terrain_offset_m[0].to_string(),
        ),
        (
            "touchdown.terrain_offset_v_m".to_string(),
            info.sample.terrain_offset_m[1].to_string(),
        ),
    ]);
    if let Some(t) = &info.table {
        meta.extend(t.metadata());
    }
    for (name, _, value) in control_values(info.control, s) {
        meta.insert(format!("touchdown.control.{name}"), value.to_string());
    }
    for ((name, _), value) in crate::scenario::INPUT_FIELDS
        .iter()
        .zip(info.sample.inputs.to_array())
    {
        meta.insert(format!("touchdown.input.{name}"), value.to_string());
    }
    // The parameters that play a part in the scenario (all, if it cannot be read).
    let scenario = crate::scenario::Scenario::from_toml(info.scenario_toml).ok();
    for p in crate::scenario::Parameter::ALL {
        if scenario.as_ref().is_none_or(|s| s.uses(p)) {
            let value = info.sample.parameters[p as usize];
            meta.insert(
                format!("touchdown.parameter.{}", p.name()),
                value.to_string(),
            );
        }
    }
    // The touchdown state a scenario gives (a table's values included), read back as the
    // values after the parameters are (`scene::trace`).
    if scenario.is_some_and(|s| s.initial.touchdown.is_some()) {
        for ((name, _), value) in crate::scenario::INITIAL_FIELDS
            .iter()
            .zip(info.sample.touchdown)
        {
            meta.insert(format!("touchdown.parameter.{name}"), value.to_string());
        }
    }
    meta
}
