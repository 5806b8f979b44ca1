//! The `[damper]` table: the crushable honeycomb dampers and their strut axes.

use super::error::ScenarioError;
use super::inputs::{Sampled, read_parameter};
use super::reader::{Reader, table};
use toml::Value;

/// One pound per square inch in pascal.
pub const PSI_PA: f64 = 6_894.757_293_168_361;

/// One stage of a crushable cartridge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    /// The stroke over which this stage crushes, m.
    pub stroke_m: f64,
    /// The crush strength of its honeycomb, psi (times the cartridge's area: its force).
    pub crush_strength_psi: f64,
}

table! {
    /// Crushable honeycomb dampers, one per leg (MODEL.md section 6).
    #[derive(Debug, Clone, PartialEq)]
    pub struct Damper;
    fn read_damper(r, sampled: &mut Sampled) with key {
        /// Whether the legs have dampers.
        enabled: bool = r.bool(key)?,
        /// Cartridge cross-section.
        area_cm2: f64 = r.positive(key)?,
        /// Stages from the first crushed to the last; one stage for a plain cartridge
        /// (`crush_strength_psi` and `usable_stroke_m`).
        stages: Vec<Stage> = read_stages(r, key, sampled)?,
        /// Whether the cartridge is pre-crushed (no initial peak).
        pre_crushed: bool = r.bool(key)?,
        /// Crush force over the first `initial_peak_stroke_m` of a cartridge that is not
        /// pre-crushed, as a multiple of the first stage's plateau.
        initial_peak_factor: f64 = r.f64_where(
            key,
            "a number of at least 1 (multiple of the plateau)",
            |x| x >= 1.0,
        )?,
        /// Stroke of the initial peak.
        initial_peak_stroke_m: f64 = r.positive(key)?,
        /// Strut axis per leg (unit vector in B, from hip to footpad), key `strut_axis`.
        strut_axes: StrutAxes = read_strut_axes(r, "strut_axis")?,
    }
}

/// The strut axis of every leg, or one per leg.
#[derive(Debug, Clone, PartialEq)]
pub enum StrutAxes {
    /// One unit axis in B for every leg, from the hip to the footpad.
    All([f64; 3]),
    /// One unit axis in B per leg, in leg order.
    PerLeg(Vec<[f64; 3]>),
}

/// The stages: `stages`, or a single one from `crush_strength_psi` and `usable_stroke_m`.
fn read_stages(
    r: &mut Reader,
    key: &'static str,
    sampled: &mut Sampled,
) -> Result<Vec<Stage>, ScenarioError> {
    let Some(v) = r.take(key) else {
        return Ok(vec![Stage {
            crush_strength_psi: read_parameter(r, "crush_strength_psi", sampled)?,
            stroke_m: r.positive("usable_stroke_m")?,
        }]);
    };
    if let Some(k) = ["crush_strength_psi", "usable_stroke_m"]
        .iter()
        .find(|k| r.has(k))
    {
        return Err(r.error(key, &v, &format!("either `stages` or `{k}`, not both")));
    }
    let allowed = "a non-empty array of { stroke_m = ..., crush_strength_psi = ... }";
    let Value::Array(a) = v.clone() else {
        return Err(r.error(key, &v, allowed));
    };
    if a.is_empty() {
        return Err(r.error(key, &v, allowed));
    }
    let mut stages = Vec::new();
    for (i, s) in a.into_iter().enumerate() {
        let Value::Table(t) = s else {
            return Err(r.error(key, &v, allowed));
        };
        let mut t = Reader::new(&format!("{}[{i}]", r.key_path(key)), t);
        let stroke_m = t.given("stroke_m", |t| t.positive("stroke_m"))?;
        let crush_strength_psi =
            t.given("crush_strength_psi", |t| t.positive("crush_strength_psi"))?;
        let (Some(stroke_m), Some(crush_strength_psi)) = (stroke_m, crush_strength_psi) else {
            return Err(r.error(
                key,
                &v,
                "every stage to give both stroke_m and crush_strength_psi",
            ));
        };
        t.finish()?;
        stages.push(Stage {
            stroke_m,
            crush_strength_psi,
        });
    }
    Ok(stages)
}

/// The strut axis of every leg, or one per leg.
fn read_strut_axes(r: &mut Reader, key: &'static str) -> Result<StrutAxes, ScenarioError> {
    let v = r.value(key)?;
    let unit = |a: [f64; 3]| {
        let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        (n > 1e-9).then(|| [a[0] / n, a[1] / n, a[2] / n])
    };
    let allowed = "a non-zero vector [x, y, z] in B, or one per leg [[x, y, z], ...]";
    Ok(match &v {
        Value::Array(a) if a.iter().all(|x| matches!(x, Value::Array(_))) => {
            let mut axes = Vec::new();
            for x in a {
                let u = unit(r.vec3(key, x)?).ok_or_else(|| r.error(key, &v, allowed))?;
                axes.push(u);
            }
            StrutAxes::PerLeg(axes)
        }
        _ => StrutAxes::All(unit(r.vec3(key, &v)?).ok_or_else(|| r.error(key, &v, allowed))?),
    })
}
