//! The `[damper]` table: the crushable honeycomb dampers and their strut axes.

use super::error::ScenarioError;
use super::inputs::{Parameter, Sampled, read_parameter};
use super::reader::Reader;
use toml::Value;

/// One pound per square inch in pascal.
pub const PSI_PA: f64 = 6_894.757_293_168_361;

/// One stage of a crushable cartridge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    pub stroke_m: f64,
    pub crush_strength_psi: f64,
}

/// Crushable honeycomb dampers, one per leg (MODEL.md section 6).
#[derive(Debug, Clone, PartialEq)]
pub struct Damper {
    pub enabled: bool,
    /// Cartridge cross-section.
    pub area_cm2: f64,
    /// Stages from the first crushed to the last; one stage for a plain cartridge.
    pub stages: Vec<Stage>,
    pub pre_crushed: bool,
    /// Crush force over the first `initial_peak_stroke_m` of a cartridge that is not
    /// pre-crushed, as a multiple of the first stage's plateau.
    pub initial_peak_factor: f64,
    pub initial_peak_stroke_m: f64,
    /// Strut axis per leg (unit vector in B, from hip to footpad).
    pub strut_axes: StrutAxes,
}

/// The strut axis of every leg, or one per leg.
#[derive(Debug, Clone, PartialEq)]
pub enum StrutAxes {
    All([f64; 3]),
    PerLeg(Vec<[f64; 3]>),
}

pub(super) fn read_damper(
    top: &mut Reader,
    d: &Damper,
    sampled: &mut Sampled,
) -> Result<Damper, ScenarioError> {
    let Some(mut r) = top.table("damper")? else {
        return Ok(d.clone());
    };
    let enabled = r.bool("enabled", d.enabled)?;
    let area_cm2 = r.positive("area_cm2", d.area_cm2)?;
    let stages = match r.take("stages") {
        Some(v) => {
            if let Some(k) = ["crush_strength_psi", "usable_stroke_m"]
                .iter()
                .find(|k| r.has(k))
            {
                return Err(r.error("stages", &v, &format!("either `stages` or `{k}`, not both")));
            }
            let allowed = "a non-empty array of { stroke_m = ..., crush_strength_psi = ... }";
            let Value::Array(a) = v.clone() else {
                return Err(r.error("stages", &v, allowed));
            };
            if a.is_empty() {
                return Err(r.error("stages", &v, allowed));
            }
            let mut stages = Vec::new();
            for (i, s) in a.into_iter().enumerate() {
                let Value::Table(t) = s else {
                    return Err(r.error("stages", &v, allowed));
                };
                let mut t = Reader::new(&format!("{}[{i}]", r.key_path("stages")), t);
                let stroke_m = t.positive("stroke_m", f64::NAN)?;
                let crush_strength_psi = t.positive("crush_strength_psi", f64::NAN)?;
                if stroke_m.is_nan() || crush_strength_psi.is_nan() {
                    return Err(r.error(
                        "stages",
                        &v,
                        "every stage to give both stroke_m and crush_strength_psi",
                    ));
                }
                t.finish()?;
                stages.push(Stage {
                    stroke_m,
                    crush_strength_psi,
                });
            }
            stages
        }
        None => vec![Stage {
            crush_strength_psi: read_parameter(
                &mut r,
                Parameter::CrushStrengthPsi,
                d.stages[0].crush_strength_psi,
                true,
                sampled,
            )?,
            stroke_m: r.positive("usable_stroke_m", d.stages[0].stroke_m)?,
        }],
    };
    let pre_crushed = r.bool("pre_crushed", d.pre_crushed)?;
    let initial_peak_factor = r.f64_where(
        "initial_peak_factor",
        d.initial_peak_factor,
        "a number of at least 1 (multiple of the plateau)",
        |x| x >= 1.0,
    )?;
    let initial_peak_stroke_m = r.positive("initial_peak_stroke_m", d.initial_peak_stroke_m)?;
    let strut_axes = match r.take("strut_axis") {
        None => d.strut_axes.clone(),
        Some(v) => {
            let unit = |a: [f64; 3]| {
                let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
                (n > 1e-9).then(|| [a[0] / n, a[1] / n, a[2] / n])
            };
            let allowed = "a non-zero vector [x, y, z] in B, or one per leg [[x, y, z], ...]";
            match &v {
                Value::Array(a) if a.iter().all(|x| matches!(x, Value::Array(_))) => {
                    let mut axes = Vec::new();
                    for x in a {
                        let u = unit(r.vec3("strut_axis", x)?)
                            .ok_or_else(|| r.error("strut_axis", &v, allowed))?;
                        axes.push(u);
                    }
                    StrutAxes::PerLeg(axes)
                }
                _ => StrutAxes::All(
                    unit(r.vec3("strut_axis", &v)?)
                        .ok_or_else(|| r.error("strut_axis", &v, allowed))?,
                ),
            }
        }
    };
    r.finish()?;
    Ok(Damper {
        enabled,
        area_cm2,
        stages,
        pre_crushed,
        initial_peak_factor,
        initial_peak_stroke_m,
        strut_axes,
    })
}
