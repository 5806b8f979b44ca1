//! The sweep file's columns: inputs, results, legs, the control loop's and the drawn
//! parameters', with their units and descriptions, and the provenance in its metadata.

use super::control::CONTROL_COLUMNS;
use crate::output::{ENGINE, field};
use crate::scenario::INPUT_FIELDS;
use crate::sweep::Shard;
use arrow_schema::{DataType, Field, Schema, SchemaRef};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Provenance stored in the schema metadata.
pub struct SweepInfo<'a> {
    /// The scenario's TOML text, as the sweep ran it.
    pub scenario_toml: &'a str,
    /// The sweep's seed.
    pub seed: u64,
    /// Samples of the whole sweep (of all its shards).
    pub samples: u64,
    /// The kernel arithmetic (`f64x8-fma`, `f64x8-nofma`, `f32x16-fma` or `f32x16-nofma`).
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
/// those it draws per sample; then those of the touchdown state's values it draws
/// (`INITIAL_FIELDS`).
#[must_use]
pub fn parameter_columns(scenario: &crate::scenario::Scenario) -> Vec<&'static str> {
    let state = scenario.initial.touchdown.map_or([false; 3], |t| {
        t.map(|d| !matches!(d, crate::scenario::Dist::Fixed(_)))
    });
    crate::scenario::Parameter::ALL
        .iter()
        .filter(|p| scenario.sampled[**p as usize].is_some())
        .map(|p| p.name())
        .chain(
            crate::scenario::INITIAL_FIELDS
                .iter()
                .zip(state)
                .filter(|(_, drawn)| *drawn)
                .map(|((name, _), _)| *name),
        )
        .collect()
}

/// Schema metadata keys of a shard file (a whole sweep has neither).
pub const SHARD_KEYS: [&str; 2] = ["touchdown.shard", "touchdown.sample_range"];

/// The schema of a sweep of a lander with `legs` legs.
#[must_use]
pub fn schema(legs: usize, info: &SweepInfo<'_>) -> SchemaRef {
    let f = |n: &str, t: DataType, u: &str, d: &str| field(n, t, u, d);
    let mut fields = input_fields();
    fields.extend(result_fields(!info.control.is_empty()));
    fields.extend(leg_fields(legs));
    fields.push(f(
        "legs_bottomed",
        DataType::UInt32,
        "1",
        "legs whose damper used up its usable stroke (0 without dampers)",
    ));
    if has_regolith(info.scenario_toml) {
        for k in 0..legs {
            for (name, unit, description) in REGOLITH_COLUMNS {
                fields.push(f(
                    &format!("leg{k}_{name}"),
                    DataType::Float64,
                    unit,
                    description,
                ));
            }
        }
    }
    if has_limits(info.scenario_toml) {
        fields.push(f(
            LIMITS_COLUMN,
            coded_texts(),
            "1",
            "the scenario's [limits] the sample broke, among axial_force, side_force, \
             acceleration and stroke_margin in that order, joined by commas (empty: none)",
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
    for (name, unit) in crate::scenario::INITIAL_FIELDS {
        if info.parameters.contains(&name) {
            fields.push(f(
                name,
                DataType::Float64,
                unit,
                "touchdown state given by the scenario, drawn per sample (MODEL.md section 8)",
            ));
        }
    }
    fields.extend(info.kept.iter().map(|f| f.as_ref().clone()));
    let meta = metadata(info);
    Arc::new(Schema::new_with_metadata(fields, meta))
}

/// The type of a text column of few values (`outcome`, `limits_broken`): per row a code
/// into one dictionary of every text the column can hold, the same in every batch and file
/// (pandas reads it as a categorical, polars as a Categorical, both compare it with text).
#[must_use]
pub fn coded_texts() -> DataType {
    DataType::Dictionary(Box::new(DataType::Int8), Box::new(DataType::Utf8))
}

/// Whether `a` and `b` are the same columns (names, types, metadata), a coded text column
/// (`coded_texts`) and a plain one (`Utf8`, as sweeps wrote `outcome` and `limits_broken`
/// before they were coded) taken as the same: for `merge` and `--resume`, which write both
/// as this engine codes them.
#[must_use]
pub fn same_columns(a: &arrow_schema::Fields, b: &arrow_schema::Fields) -> bool {
    let plain = |f: &arrow_schema::FieldRef| match f.data_type() {
        DataType::Dictionary(_, value) => f.as_ref().clone().with_data_type(*value.clone()),
        _ => f.as_ref().clone(),
    };
    a.len() == b.len() && a.iter().zip(b.iter()).all(|(x, y)| plain(x) == plain(y))
}

/// The fields of a sample's index, seed, inputs and terrain.
fn input_fields() -> Vec<Field> {
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
    ]);
    fields
}

/// The fields of a sample's results, up to the legs. With a control loop (`controlled`),
/// a lander may end `held`, and thrust adds to the accelerometer's reading; the
/// descriptions of a passive sweep say what they said before there was either.
fn result_fields(controlled: bool) -> Vec<Field> {
    let f = |n: &str, t: DataType, u: &str, d: &str| field(n, t, u, d);
    let pick =
        |passive: &'static str, thrust: &'static str| if controlled { thrust } else { passive };
    vec![
        f(
            "outcome",
            coded_texts(),
            "1",
            pick(
                "stable, tipped, sliding, bouncing or diverged",
                "stable, tipped, sliding, bouncing, diverged or held",
            ),
        ),
        f(
            "decided_s",
            DataType::Float64,
            "s",
            pick(
                "time the outcome was decided (t_max for sliding and bouncing)",
                "time the outcome was decided (t_max for sliding, bouncing and held)",
            ),
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
            pick(
                "peak contact acceleration of the CG (accelerometer reading)",
                "peak specific force of the CG over the mass: contact and thrust, not gravity \
                 (accelerometer reading)",
            ),
        ),
        f(
            "peak_acceleration_z_body_m_s2",
            DataType::Float64,
            "m/s^2",
            pick(
                "peak contact acceleration along Z_B (instruments' shock)",
                "peak specific force over the mass along Z_B: contact and thrust (instruments' \
                 shock)",
            ),
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
    ]
    .into_iter()
    .chain(touchdown_fields())
    .collect()
}

/// The state in which the lander met the surface (`reference::touchdown`), at the start of
/// the first contact's step, in the surface plane's frame: nullable (null: never touched,
/// and the azimuths where the speed along the surface is 0).
pub const TOUCHDOWN_COLUMNS: [(&str, &str, &str); 9] = [
    (
        "touchdown_normal_speed_m_s",
        "m/s",
        "speed towards the surface at the first contact, -n . v (null: never touched)",
    ),
    (
        "touchdown_tangential_speed_m_s",
        "m/s",
        "speed along the surface at the first contact",
    ),
    (
        "touchdown_tangential_azimuth_deg",
        "deg",
        "direction of the velocity along the surface at the first contact, from downhill, \
         positive towards n x downhill (null where that speed is 0)",
    ),
    (
        "touchdown_tangential_azimuth_body_deg",
        "deg",
        "the same from X_B projected on the surface (relative to the legs)",
    ),
    (
        "touchdown_tilt_deg",
        "deg",
        "tilt of Z_B from the surface normal at the first contact",
    ),
    (
        "touchdown_rate_x_deg_s",
        "deg/s",
        "body rate about X_B at the first contact",
    ),
    (
        "touchdown_rate_y_deg_s",
        "deg/s",
        "body rate about Y_B at the first contact",
    ),
    (
        "touchdown_rate_z_deg_s",
        "deg/s",
        "body rate about Z_B at the first contact",
    ),
    (
        "touchdown_first_leg",
        "1",
        "the leg that touched first (the deepest on the first contact's step)",
    ),
];

fn touchdown_fields() -> impl Iterator<Item = Field> {
    TOUCHDOWN_COLUMNS.iter().map(|&(name, unit, description)| {
        let t = if name == "touchdown_first_leg" {
            DataType::UInt32
        } else {
            DataType::Float64
        };
        field(name, t, unit, description).with_nullable(true)
    })
}

/// Each leg's regolith columns, in a sweep of a scenario on regolith (after
/// `legs_bottomed`): name after `leg{k}_`, unit, description.
pub const REGOLITH_COLUMNS: [(&str, &str, &str); 2] = [
    (
        "sinkage_m",
        "m",
        "depth of the footpad's last footprint in the regolith, once unloaded (MODEL.md 5.1)",
    ),
    (
        "soil_absorbed_j",
        "J",
        "energy the regolith absorbed for good under the footpad",
    ),
];

/// Whether the scenario text puts the lander on regolith (`surface.kind = "regolith"`: its
/// sweep has the `REGOLITH_COLUMNS` of every leg).
#[must_use]
pub fn has_regolith(scenario_toml: &str) -> bool {
    scenario_toml.parse::<toml::Table>().is_ok_and(|t| {
        t.get("surface")
            .and_then(|s| s.get("kind"))
            .and_then(toml::Value::as_str)
            == Some("regolith")
    })
}

/// The column of the limits a sample broke, in a sweep of a scenario with `[limits]`.
pub const LIMITS_COLUMN: &str = "limits_broken";

/// Whether the scenario text gives `[limits]` (its sweep has `LIMITS_COLUMN`).
#[must_use]
pub fn has_limits(scenario_toml: &str) -> bool {
    scenario_toml
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("limits"))
}

/// Each leg's strut columns (MODEL.md section 9) after its first three: name, type, unit,
/// description; the times and the margin are null where they have no value.
const STRUT_COLUMNS: [(&str, DataType, &str, &str); 6] = [
    (
        "peak_axial_force_n",
        DataType::Float64,
        "N",
        "peak axial strut load: the footpad's force along the strut, compressive positive",
    ),
    (
        "peak_axial_force_s",
        DataType::Float64,
        "s",
        "start of the step of the peak axial load (null: never loaded)",
    ),
    (
        "peak_side_force_n",
        DataType::Float64,
        "N",
        "peak side load: the footpad's force across the strut",
    ),
    (
        "peak_side_force_s",
        DataType::Float64,
        "s",
        "start of the step of the peak side load (null: never loaded)",
    ),
    (
        "stroke_margin_m",
        DataType::Float64,
        "m",
        "usable damper stroke less the final stroke (0: bottomed; null without dampers)",
    ),
    (
        "bottomed",
        DataType::Boolean,
        "1",
        "the damper used up its usable stroke",
    ),
];

/// The fields of each leg's results.
fn leg_fields(legs: usize) -> Vec<Field> {
    let f = |n: &str, t: DataType, u: &str, d: &str| field(n, t, u, d);
    let mut fields = Vec::with_capacity((3 + STRUT_COLUMNS.len()) * legs);
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
        for (name, t, unit, description) in STRUT_COLUMNS {
            let nullable = name.ends_with("_s") || name == "stroke_margin_m";
            fields.push(f(&format!("leg{k}_{name}"), t, unit, description).with_nullable(nullable));
        }
    }
    fields
}

/// The provenance stored in the schema metadata: engine, kind, scenario, seed, samples,
/// lane type, the table of inputs, and a shard's slice.
fn metadata(info: &SweepInfo<'_>) -> BTreeMap<String, String> {
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
    meta
}
