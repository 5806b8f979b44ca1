//! Rows of a sweep as one record batch of its schema, column by column.

use super::schema::LIMITS_COLUMN;
use crate::control::ControlSummary;
use crate::output::read::Texts;
use crate::reference::Outcome;
use crate::reference::outcome::LegSummary;
use crate::reference::touchdown::{Met, Touchdown};
use crate::scenario::{Broken, INPUT_FIELDS, LIMIT_NAMES};
use crate::sweep::Row;
use arrow_array::builder::{BooleanBuilder, Float64Builder, UInt32Builder, UInt64Builder};
use arrow_array::cast::AsArray;
use arrow_array::types::Int8Type;
use arrow_array::{ArrayRef, DictionaryArray, Int8Array, RecordBatch, StringArray};
use arrow_schema::SchemaRef;
use glam::DVec3;
use std::sync::{Arc, LazyLock};

// An outcome's code is its discriminant (`o as i8`): `Outcome::ALL` lists them in that order.
const _: () = {
    let mut i = 0;
    while i < Outcome::ALL.len() {
        assert!(
            Outcome::ALL[i] as usize == i,
            "Outcome::ALL in the order of the codes"
        );
        i += 1;
    }
};

// A set of broken limits is coded by its bits, in an `i8`.
const _: () = assert!(
    LIMIT_NAMES.len() <= 7,
    "the sets of limits fit the codes of an i8"
);

/// The dictionary of the `outcome` column (`schema::coded_texts`): every outcome's name,
/// at its code (its place in `Outcome::ALL`).
static OUTCOME_NAMES: LazyLock<ArrayRef> = LazyLock::new(|| {
    Arc::new(StringArray::from_iter_values(
        Outcome::ALL.map(Outcome::name),
    ))
});

/// The dictionary of the `limits_broken` column: every set of broken limits as
/// `Broken::names` writes it, at its bits.
static LIMIT_SETS: LazyLock<ArrayRef> = LazyLock::new(|| {
    Arc::new(StringArray::from_iter_values(
        (0..1u8 << LIMIT_NAMES.len()).map(|bits| Broken(bits).names()),
    ))
});

/// The columns of `b` as a batch of `schema` (the same columns, `schema::same_columns`),
/// its coded columns (`outcome`, `limits_broken`) coded into this engine's dictionaries as
/// the batches a sweep makes: for a batch read back from a file (`Rebatcher::push`, for
/// `merge` and `--resume`) or joined from several (`SweepWriter::write_batch`), since a
/// Parquet reader rebuilds each row group's dictionary from the texts it holds, a file
/// written before the coded outcome holds plain text, joining batches joins their
/// dictionaries, and an Arrow IPC file holds one dictionary per column.
pub fn recoded(b: &RecordBatch, schema: &SchemaRef) -> anyhow::Result<RecordBatch> {
    type Code = fn(&str) -> Option<i8>;
    let mut columns = b.columns().to_vec();
    for (column, field) in columns.iter_mut().zip(schema.fields()) {
        if !matches!(field.data_type(), arrow_schema::DataType::Dictionary(..)) {
            continue;
        }
        let (names, code): (&ArrayRef, Code) = match field.name().as_str() {
            "outcome" => (&OUTCOME_NAMES, |t| Outcome::from_name(t).map(|o| o as i8)),
            LIMITS_COLUMN => (&LIMIT_SETS, |t| {
                let set = Broken::parse(t);
                (set.names() == t).then_some(set.0 as i8)
            }),
            _ => continue,
        };
        // Coded already, into a dictionary of the same texts (a file of this engine).
        if column.data_type() == field.data_type()
            && column
                .as_any_dictionary_opt()
                .is_some_and(|d| d.values().to_data() == names.to_data())
        {
            continue;
        }
        let name = field.name();
        let texts = Texts::of(column.as_ref())
            .ok_or_else(|| anyhow::anyhow!("the column {name} is not text"))?;
        let codes = texts.iter().map(|t| {
            t.and_then(code)
                .ok_or_else(|| anyhow::anyhow!("{t:?} in the column {name} is none of its texts"))
        });
        *column = coded(codes.collect::<anyhow::Result<_>>()?, names)?;
    }
    Ok(RecordBatch::try_new(schema.clone(), columns)?)
}

/// A coded text column (`schema::coded_texts`) of `codes` into `names`.
fn coded(codes: Vec<i8>, names: &ArrayRef) -> anyhow::Result<ArrayRef> {
    let codes = Int8Array::from(codes);
    Ok(Arc::new(DictionaryArray::<Int8Type>::try_new(
        codes,
        names.clone(),
    )?))
}

/// The value of the control column `name` (`CONTROL_COLUMNS`) in a lander's summary of its
/// control loop (firings as a number), for sweep rows and traces alike; `None` for a name
/// that is not one.
#[must_use]
pub fn control_value(name: &str) -> Option<fn(&ControlSummary) -> f64> {
    fn descent(c: &ControlSummary) -> crate::control::DescentDraw {
        c.descent.unwrap_or_default()
    }
    let get: fn(&ControlSummary) -> f64 = match name {
        "propellant_kg" => |c| c.propellant_kg,
        "thrust_on_time_s" => |c| c.on_time_s,
        "firings" => |c| f64::from(c.firings),
        "hold_down_impulse_n_s" => |c| c.hold_down_impulse_n_s,
        "hold_down_thrust_n" => |c| c.hold_down_thrust_n,
        "hold_down_duration_s" => |c| c.hold_down_duration_s,
        "attitude_kp_n_m_per_rad" => |c| c.kp_n_m_per_rad,
        "attitude_kd_n_m_s_per_rad" => |c| c.kd_n_m_s_per_rad,
        "descent_start_altitude_m" => |c| descent(c).start_altitude_m,
        "descent_start_speed_m_s" => |c| descent(c).start_speed_m_s,
        "descent_braking_m_s2" => |c| descent(c).braking_m_s2,
        "descent_gain_per_s" => |c| descent(c).gain_per_s,
        "descent_release_speed_m_s" => |c| descent(c).release_speed_m_s,
        "release_time_s" => |c| c.release_time_s,
        "release_altitude_m" => |c| c.release_altitude_m,
        "release_vx_m_s" => |c| c.release_velocity_m_s[0],
        "release_vy_m_s" => |c| c.release_velocity_m_s[1],
        "release_vz_m_s" => |c| c.release_velocity_m_s[2],
        _ => return None,
    };
    Some(get)
}
/// The columns of `TOUCHDOWN_COLUMNS` (null where a lander never touched, and the
/// azimuths where its speed along the surface was 0), into `cols`.
fn touchdown_columns(rows: &[Row], cols: &mut Vec<ArrayRef>) {
    let values: [fn(&Touchdown) -> f64; 8] = [
        |t| t.normal_speed_m_s,
        |t| t.tangential_speed_m_s,
        |t| t.tangential_azimuth_deg,
        |t| t.tangential_azimuth_body_deg,
        |t| t.tilt_deg,
        |t| t.rate_deg_s[0],
        |t| t.rate_deg_s[1],
        |t| t.rate_deg_s[2],
    ];
    for value in values {
        let mut b = Float64Builder::with_capacity(rows.len());
        for r in rows {
            b.append_option(
                r.summary
                    .touchdown
                    .as_ref()
                    .map(value)
                    .filter(|x| !x.is_nan()),
            );
        }
        cols.push(Arc::new(b.finish()));
    }
    let mut leg = UInt32Builder::with_capacity(rows.len());
    for r in rows {
        leg.append_option(r.summary.touchdown.map(|t| t.first_leg));
    }
    cols.push(Arc::new(leg.finish()));
}

/// One quantity of a touchdown state.
type StateValue = fn(&Touchdown) -> f64;

/// The release columns of the touchdown state (`release_normal_speed_m_s` ...), in the
/// order of `TOUCHDOWN_COLUMNS`: the state a descent released the lander in, in the frame
/// of its surface plane, as the touchdown state is at the first contact.
const RELEASE_STATE: [(&str, StateValue); 8] = [
    ("release_normal_speed_m_s", |t| t.normal_speed_m_s),
    ("release_tangential_speed_m_s", |t| t.tangential_speed_m_s),
    ("release_tangential_azimuth_deg", |t| {
        t.tangential_azimuth_deg
    }),
    ("release_tangential_azimuth_body_deg", |t| {
        t.tangential_azimuth_body_deg
    }),
    ("release_tilt_deg", |t| t.tilt_deg),
    ("release_rate_x_deg_s", |t| t.rate_deg_s[0]),
    ("release_rate_y_deg_s", |t| t.rate_deg_s[1]),
    ("release_rate_z_deg_s", |t| t.rate_deg_s[2]),
];

/// The state a descent released the lander of `r` in, on its surface plane (`None`: no
/// descent, or contact came first).
fn release_state(r: &Row) -> Option<Touchdown> {
    let c = r.summary.control.as_deref()?;
    if c.release_time_s.is_nan() {
        return None;
    }
    let surface = crate::slope::Surface::of(&r.sample);
    let v = DVec3::from_array;
    let met = Met {
        velocity_m_s: v(c.release_velocity_m_s),
        rate_rad_s: v(c.release_rate_rad_s),
        x_body: v(c.release_axes[0]),
        z_body: v(c.release_axes[1]),
        first_leg: 0,
    };
    Some(Touchdown::of(
        &met,
        surface.normal,
        surface.tangent_u,
        surface.tangent_v,
    ))
}

/// Leg `k`'s strut columns (`schema::STRUT_COLUMNS`), into `cols`.
fn strut_columns(rows: &[Row], k: usize, cols: &mut Vec<ArrayRef>) {
    let leg = |r: &Row| r.summary.legs[k];
    let options: [fn(&LegSummary) -> Option<f64>; 5] = [
        |l| Some(l.peak_axial_force_n),
        |l| l.peak_axial_force_s,
        |l| Some(l.peak_side_force_n),
        |l| l.peak_side_force_s,
        |l| l.stroke_margin_m,
    ];
    for get in options {
        let mut b = Float64Builder::with_capacity(rows.len());
        rows.iter().for_each(|r| b.append_option(get(&leg(r))));
        cols.push(Arc::new(b.finish()));
    }
    let mut b = BooleanBuilder::with_capacity(rows.len());
    rows.iter().for_each(|r| b.append_value(leg(r).bottomed));
    cols.push(Arc::new(b.finish()));
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
    let outcomes = rows.iter().map(|r| r.summary.outcome as i8).collect();
    cols.push(coded(outcomes, &OUTCOME_NAMES)?);
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
    touchdown_columns(rows, &mut cols);
    for k in 0..legs {
        cols.push(f64s(&|r| r.summary.legs[k].peak_normal_force_n));
        cols.push(f64s(&|r| r.summary.legs[k].stroke_m));
        cols.push(f64s(&|r| r.summary.legs[k].absorbed_j));
        strut_columns(rows, k, &mut cols);
    }
    cols.push(u32s(&|r| r.summary.legs_bottomed()));
    let control = |r: &Row| r.summary.control.as_deref().copied().unwrap_or_default();
    let computed = schema.fields().len() - kept.len();
    for field in schema.fields()[..computed].iter().skip(cols.len()) {
        cols.push(match field.name().as_str() {
            "firings" => u32s(&|r| control(r).firings),
            LIMITS_COLUMN => {
                let sets = rows.iter();
                coded(
                    sets.map(|r| r.summary.limits_broken.unwrap_or_default().0 as i8)
                        .collect(),
                    &LIMIT_SETS,
                )?
            }
            other if let Some((k, value)) = regolith_value(other) => {
                f64s(&|r| value(&r.summary.legs[k]))
            }
            other if let Some(value) = control_value(other) => f64s(&|r| value(&control(r))),
            other if let Some((_, value)) = RELEASE_STATE.iter().find(|c| c.0 == other) => {
                f64s(&|r| release_state(r).as_ref().map_or(f64::NAN, value))
            }
            other => match crate::scenario::Parameter::ALL
                .iter()
                .find(|p| p.name() == other)
            {
                Some(&p) => f64s(&|r| r.sample.parameters[p as usize]),
                None => match crate::scenario::INITIAL_FIELDS
                    .iter()
                    .position(|(name, _)| *name == other)
                {
                    Some(j) => f64s(&|r| r.sample.touchdown[j]),
                    None => anyhow::bail!("no column {other} in a sweep"),
                },
            },
        });
    }
    cols.extend(kept);
    Ok(RecordBatch::try_new(schema.clone(), cols)?)
}

/// A leg's value in a summary.
type LegValue = fn(&LegSummary) -> f64;

/// The leg and the value of a regolith column (`REGOLITH_COLUMNS`) by its name.
fn regolith_value(name: &str) -> Option<(usize, LegValue)> {
    let (k, rest) = name.strip_prefix("leg")?.split_once('_')?;
    let value: LegValue = match rest {
        "sinkage_m" => |l| l.sinkage_m,
        "soil_absorbed_j" => |l| l.soil_absorbed_j,
        _ => return None,
    };
    Some((k.parse().ok()?, value))
}
