//! The time history of one sample (MODEL.md section 9): one row per step, or per
//! `every` steps, as an Arrow IPC file written batch by batch.

use super::{AtomicFile, ENGINE, IpcWriter, field};
use crate::reference::{Model, StepReport, Summary};
use crate::sampling::Sample;
use arrow_array::{ArrayRef, Float64Array, RecordBatch};
use arrow_schema::{DataType, Schema};
use glam::{DMat3, EulerRot};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// Rows per record batch.
const BATCH_ROWS: usize = 8192;

/// Columns of the body, then 7 columns per leg.
fn columns(legs: usize) -> Vec<(String, &'static str, String)> {
    let mut c: Vec<(String, &'static str, String)> = [
        ("t_s", "s", "time at the start of the step"),
        ("dt_s", "s", "length of the step"),
        ("x_m", "m", "CG position, X_I"),
        ("y_m", "m", "CG position, Y_I"),
        ("z_m", "m", "CG position, Z_I (up)"),
        ("vx_m_s", "m/s", "CG velocity, X_I"),
        ("vy_m_s", "m/s", "CG velocity, Y_I"),
        ("vz_m_s", "m/s", "CG velocity, Z_I"),
        ("ax_m_s2", "m/s^2", "CG acceleration dv/dt, X_I"),
        ("ay_m_s2", "m/s^2", "CG acceleration dv/dt, Y_I"),
        (
            "az_m_s2",
            "m/s^2",
            "CG acceleration dv/dt, Z_I (gravity included)",
        ),
        (
            "accel_z_body_m_s2",
            "m/s^2",
            "contact acceleration along Z_B (what an accelerometer on the body axis reads)",
        ),
        ("qw", "1", "attitude quaternion body to I, scalar part"),
        ("qx", "1", "attitude quaternion, x"),
        ("qy", "1", "attitude quaternion, y"),
        ("qz", "1", "attitude quaternion, z"),
        (
            "roll_deg",
            "deg",
            "Euler roll phi, R_IB = Rz(psi) Ry(theta) Rx(phi)",
        ),
        ("pitch_deg", "deg", "Euler pitch theta"),
        ("yaw_deg", "deg", "Euler yaw psi"),
        ("rate_x_deg_s", "deg/s", "body rate about X_B"),
        ("rate_y_deg_s", "deg/s", "body rate about Y_B"),
        ("rate_z_deg_s", "deg/s", "body rate about Z_B"),
    ]
    .iter()
    .map(|(n, u, d)| (n.to_string(), *u, d.to_string()))
    .collect();
    for k in 0..legs {
        for (n, u, d) in [
            ("tip_x_m", "m", "footpad position, X_I"),
            ("tip_y_m", "m", "footpad position, Y_I"),
            ("tip_z_m", "m", "footpad position, Z_I"),
            (
                "penetration_m",
                "m",
                "depth below the local surface (negative: clearance)",
            ),
            ("normal_force_n", "N", "normal contact force"),
            ("friction_force_n", "N", "friction force magnitude"),
            ("stroke_m", "m", "damper stroke"),
        ] {
            c.push((format!("leg{k}_{n}"), u, format!("leg {k}: {d}")));
        }
    }
    c
}

/// Appends the row of `r` to the columns `data` (`buf` holds it on the way).
fn push_row(model: &Model, r: &StepReport, buf: &mut Vec<f64>, data: &mut [Vec<f64>]) {
    row(model, r, buf);
    for (c, v) in data.iter_mut().zip(buf.iter()) {
        c.push(*v);
    }
}

/// One row of the trace from a step report.
fn row(model: &Model, r: &StepReport, out: &mut Vec<f64>) {
    out.clear();
    let b = &r.body;
    let acc = r.force_n / model.mass_kg;
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
    for l in &r.legs {
        out.extend_from_slice(&[
            l.tip_m.x,
            l.tip_m.y,
            l.tip_m.z,
            l.penetration_m,
            l.normal_n,
            l.friction_n,
            l.stroke_m,
        ]);
    }
}

/// Provenance and results stored in the schema metadata of a trace.
pub struct TraceInfo<'a> {
    pub scenario_toml: &'a str,
    pub sweep_seed: u64,
    pub sample: &'a Sample,
    pub summary: &'a Summary,
}

/// Runs `sample` with the reference model and writes every `every`-th step to `path`, the
/// state at the start of each, and last the state at the decision. Returns the number of
/// rows written.
pub fn write(path: &Path, model: &Model, info: &TraceInfo<'_>, every: u64) -> anyhow::Result<u64> {
    let cols = columns(model.legs.len());
    let fields: Vec<_> = cols
        .iter()
        .map(|(n, u, d)| field(n, DataType::Float64, u, d))
        .collect();
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
    ]);
    for ((name, _), value) in crate::scenario::INPUT_FIELDS
        .iter()
        .zip(info.sample.inputs.to_array())
    {
        meta.insert(format!("touchdown.input.{name}"), value.to_string());
    }
    let schema = Arc::new(Schema::new_with_metadata(fields, meta));

    let (file, out) = AtomicFile::create(path)?;
    let mut writer = IpcWriter::new(&file, out, &schema)?;
    let mut data: Vec<Vec<f64>> = vec![Vec::with_capacity(BATCH_ROWS); cols.len()];
    let mut buf = Vec::with_capacity(cols.len());
    let mut rows = 0u64;
    let mut index = 0u64;
    let mut failure: Option<anyhow::Error> = None;
    let flush = |data: &mut Vec<Vec<f64>>, writer: &mut IpcWriter| -> anyhow::Result<()> {
        let arrays: Vec<ArrayRef> = data
            .iter_mut()
            .map(|c| Arc::new(Float64Array::from(std::mem::take(c))) as ArrayRef)
            .collect();
        writer.write(&RecordBatch::try_new(schema.clone(), arrays)?)?;
        Ok(())
    };
    let (_, end) = crate::reference::run::run_to_end(model, info.sample, |report| {
        if failure.is_some() {
            return;
        }
        if index.is_multiple_of(every) {
            push_row(model, report, &mut buf, &mut data);
            rows += 1;
            if data[0].len() >= BATCH_ROWS
                && let Err(e) = flush(&mut data, &mut writer)
            {
                failure = Some(e);
            }
        }
        index += 1;
    });
    if let Some(e) = failure {
        return Err(e);
    }
    // The last row is the state at the decision, whatever `every`.
    push_row(model, &end, &mut buf, &mut data);
    rows += 1;
    if !data[0].is_empty() {
        flush(&mut data, &mut writer)?;
    }
    file.commit(writer.finish()?)?;
    Ok(rows)
}
