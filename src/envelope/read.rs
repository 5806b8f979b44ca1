//! The columns the envelope is built from, read from a sweep file batch by batch: each
//! sample's x and y, slope, facing and outcome, and whether it broke a limit; the samples
//! left out, counted by why.

use super::plane::Facing;
use crate::output::read::{Texts, format_of, open, outcome_of};
use anyhow::{anyhow, bail};
use arrow_array::cast::AsArray;
use arrow_array::types::{
    Float32Type, Float64Type, Int8Type, Int16Type, Int32Type, Int64Type, UInt8Type, UInt16Type,
    UInt32Type, UInt64Type,
};
use arrow_array::{Array, ArrayRef, RecordBatch};
use arrow_schema::{DataType, Schema};
use std::path::Path;

/// The column that tells a sample that never touched: null where it did not.
pub(super) const TOUCHED: &str = "touchdown_normal_speed_m_s";

/// The column of the limits a sample broke (scenario `[limits]`): empty when none.
pub(super) const LIMITS_BROKEN: &str = "limits_broken";

/// The samples kept, column by column, and those left out.
pub(super) struct Samples {
    pub(super) x: Vec<f64>,
    pub(super) y: Vec<f64>,
    pub(super) slope_deg: Vec<f64>,
    /// Leg-downhill or side-downhill (only with `--azimuth`; else all `Facing::All`).
    pub(super) facing: Vec<Facing>,
    /// Index into `Outcome::ALL`.
    pub(super) outcome: Vec<u8>,
    /// Whether the sample broke a limit (`limits_broken` not empty).
    pub(super) broke: Vec<bool>,
    /// Rows of the file.
    pub(super) rows: u64,
    /// Samples that never touched (`touchdown_normal_speed_m_s` null).
    pub(super) never_touched: u64,
    /// Samples that touched but have no value of x or y (null, NaN or infinite: the
    /// tangential azimuth of a sample with no speed along the surface).
    pub(super) no_value: u64,
    /// Samples that touched with a value of x, and with one of y (finite).
    pub(super) with_value: (u64, u64),
    /// Whether the file has a `limits_broken` column.
    pub(super) limits: bool,
}

/// A sweep file's schema checked for what the envelope reads: a sweep, numeric x and y
/// columns; their units (from the field metadata).
pub(super) fn check_columns(
    path: &Path,
    schema: &Schema,
    (x, y): (&str, &str),
) -> anyhow::Result<(String, String)> {
    match schema.metadata().get("touchdown.kind").map(String::as_str) {
        Some("sweep") => {}
        Some(kind) => bail!(
            "{} is not a sweep file of touchdown (it is a {kind} file)",
            path.display()
        ),
        None => bail!("{} is not a sweep file of touchdown", path.display()),
    }
    let unit = |name: &str, flag: &str| -> anyhow::Result<String> {
        let field = schema.field_with_name(name).map_err(|_| {
            anyhow!(
                "{flag} {name}: {} has no column {name} (numeric columns: {})",
                path.display(),
                numeric_columns(schema)
            )
        })?;
        if !is_numeric(field.data_type()) {
            bail!(
                "{flag} {name}: the column {name} of {} is not numeric ({}); numeric \
                 columns: {}",
                path.display(),
                field.data_type(),
                numeric_columns(schema)
            );
        }
        Ok(field.metadata().get("unit").cloned().unwrap_or_default())
    };
    Ok((unit(x, "--x")?, unit(y, "--y")?))
}

/// Whether a column of `t` reads as numbers.
fn is_numeric(t: &DataType) -> bool {
    matches!(
        t,
        DataType::Float64
            | DataType::Float32
            | DataType::Int8
            | DataType::Int16
            | DataType::Int32
            | DataType::Int64
            | DataType::UInt8
            | DataType::UInt16
            | DataType::UInt32
            | DataType::UInt64
    )
}

/// The numeric columns of `schema`, for an error message: the first few and how many more.
fn numeric_columns(schema: &Schema) -> String {
    let names: Vec<&str> = schema
        .fields()
        .iter()
        .filter(|f| is_numeric(f.data_type()))
        .map(|f| f.name().as_str())
        .collect();
    if names.len() <= 12 {
        return names.join(", ");
    }
    format!("{}, ... ({} in all)", names[..12].join(", "), names.len())
}

/// A numeric column as `f64`, nulls as NaN.
fn numbers(a: &ArrayRef) -> Vec<f64> {
    macro_rules! each {
        ($($t:ty),*) => {
            $(if let Some(p) = a.as_primitive_opt::<$t>() {
                return p.iter().map(|v| v.map_or(f64::NAN, |v| v as f64)).collect();
            })*
        };
    }
    each!(
        Float64Type,
        Float32Type,
        Int8Type,
        Int16Type,
        Int32Type,
        Int64Type,
        UInt8Type,
        UInt16Type,
        UInt32Type,
        UInt64Type
    );
    vec![f64::NAN; a.len()]
}

/// The leg azimuths in B (deg) and the half width of a leg's sector (deg), for `--azimuth`.
pub(super) type Legs = (Vec<f64>, f64);

/// Reads the samples of the sweep file at `path` (its schema already checked by
/// `check_columns`); with `legs`, each sample's facing.
pub(super) fn samples(
    path: &Path,
    (x, y): (&str, &str),
    legs: Option<&Legs>,
) -> anyhow::Result<Samples> {
    let (_, batches) = open(path, format_of(path)?)?;
    let mut s = Samples {
        x: Vec::new(),
        y: Vec::new(),
        slope_deg: Vec::new(),
        facing: Vec::new(),
        outcome: Vec::new(),
        broke: Vec::new(),
        rows: 0,
        never_touched: 0,
        no_value: 0,
        with_value: (0, 0),
        limits: false,
    };
    for b in batches {
        s.push(path, &b?, (x, y), legs)?;
    }
    Ok(s)
}

impl Samples {
    /// Adds the rows of one batch.
    fn push(
        &mut self,
        path: &Path,
        b: &RecordBatch,
        (x, y): (&str, &str),
        legs: Option<&Legs>,
    ) -> anyhow::Result<()> {
        let column = |name: &str| {
            b.column_by_name(name)
                .ok_or_else(|| anyhow!("{}: no column {name}", path.display()))
        };
        let float = |name: &str| -> anyhow::Result<Vec<f64>> {
            let c = column(name)?;
            if c.data_type() != &DataType::Float64 {
                bail!("{}: no Float64 column {name}", path.display());
            }
            Ok(numbers(c))
        };
        let (xs, ys, slope) = (
            numbers(column(x)?),
            numbers(column(y)?),
            float("slope_deg")?,
        );
        let touched = b.column_by_name(TOUCHED);
        let outcome = column("outcome")?.as_ref();
        let outcome = Texts::of(outcome)
            .ok_or_else(|| anyhow!("{}: the outcome column is not text", path.display()))?;
        let broken = match b.column_by_name(LIMITS_BROKEN) {
            Some(c) => Some(Texts::of(c.as_ref()).ok_or_else(|| {
                anyhow!(
                    "{}: the column {LIMITS_BROKEN} is not text ({})",
                    path.display(),
                    c.data_type()
                )
            })?),
            None => None,
        };
        self.limits |= broken.is_some();
        let relative = match legs {
            Some(_) => {
                let (azimuth, yaw) = (float("downhill_azimuth_deg")?, float("yaw_deg")?);
                azimuth
                    .iter()
                    .zip(&yaw)
                    .map(|(a, w)| crate::stats::relative_azimuth_deg(*a, *w))
                    .collect()
            }
            None => Vec::new(),
        };
        self.rows += b.num_rows() as u64;
        for i in 0..b.num_rows() {
            if touched.is_some_and(|c| c.is_null(i)) {
                self.never_touched += 1;
                continue;
            }
            self.with_value.0 += u64::from(xs[i].is_finite());
            self.with_value.1 += u64::from(ys[i].is_finite());
            if !(xs[i].is_finite() && ys[i].is_finite()) {
                self.no_value += 1;
                continue;
            }
            let o = outcome_of(outcome.get(i).unwrap_or(""), path)?;
            self.x.push(xs[i]);
            self.y.push(ys[i]);
            self.slope_deg.push(slope[i]);
            self.outcome.push(o as u8);
            self.broke.push(
                broken
                    .as_ref()
                    .is_some_and(|c| c.get(i).is_some_and(|t| !t.is_empty())),
            );
            self.facing.push(match legs {
                Some(l) => Facing::of(relative[i], l),
                None => Facing::All,
            });
        }
        Ok(())
    }
}
