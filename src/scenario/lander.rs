//! The `[lander]` table: the lander's mass, inertia and leg geometry.

use super::error::ScenarioError;
use super::inputs::{Parameter, Sampled, read_parameter};
use super::reader::Reader;
use toml::Value;

/// Where the lander's legs are.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// `legs` footpads evenly spaced on a circle of `footpad_radius_m` around Z_B,
    /// `cg_height_m` below the CG, the first at `first_leg_azimuth_deg` from X_B.
    Regular {
        legs: usize,
        footpad_radius_m: f64,
        cg_height_m: f64,
        first_leg_azimuth_deg: f64,
    },
    /// Explicit footpad positions in B, m.
    Tips(Vec<[f64; 3]>),
}

/// The lander (MODEL.md section 3).
#[derive(Debug, Clone, PartialEq)]
pub struct Lander {
    pub mass_kg: f64,
    /// Principal moments of inertia about X_B, Y_B, Z_B.
    pub inertia_kg_m2: [f64; 3],
    pub geometry: Geometry,
}

impl Lander {
    /// The footpads in B (CG at the origin) with the dampers uncrushed, m.
    #[must_use]
    pub fn tips_m(&self) -> Vec<[f64; 3]> {
        match &self.geometry {
            Geometry::Regular {
                legs,
                footpad_radius_m,
                cg_height_m,
                first_leg_azimuth_deg,
            } => (0..*legs)
                .map(|i| {
                    let az = first_leg_azimuth_deg.to_radians()
                        + std::f64::consts::TAU * i as f64 / *legs as f64;
                    [
                        footpad_radius_m * libm::cos(az),
                        footpad_radius_m * libm::sin(az),
                        -cg_height_m,
                    ]
                })
                .collect(),
            Geometry::Tips(t) => t.clone(),
        }
    }
}

pub(super) fn read_lander(
    top: &mut Reader,
    d: &Lander,
    sampled: &mut Sampled,
) -> Result<Lander, ScenarioError> {
    let Some(mut r) = top.table("lander")? else {
        return Ok(d.clone());
    };
    let mass_kg = read_parameter(&mut r, Parameter::MassKg, d.mass_kg, true, sampled)?;
    let inertia_kg_m2 = match r.take("inertia_kg_m2") {
        None => d.inertia_kg_m2,
        Some(v) => {
            let i = r.vec3("inertia_kg_m2", &v)?;
            if i.iter().any(|x| *x <= 0.0) {
                return Err(r.error(
                    "inertia_kg_m2",
                    &v,
                    "three principal moments greater than 0",
                ));
            }
            // A rigid body's principal moments obey the triangle inequality; equality is a
            // flat plate. The relative slack absorbs rounding in values typed from decimals.
            for k in 0..3 {
                let (a, b, c) = (i[k], i[(k + 1) % 3], i[(k + 2) % 3]);
                if a > (b + c) * (1.0 + 1e-12) {
                    return Err(r.error(
                        "inertia_kg_m2",
                        &v,
                        "principal moments of a rigid body: each at most the sum of the other two (triangle inequality)",
                    ));
                }
            }
            i
        }
    };
    let Geometry::Regular {
        legs: d_legs,
        footpad_radius_m: d_radius,
        cg_height_m: d_height,
        first_leg_azimuth_deg: d_az,
    } = d.geometry
    else {
        unreachable!("the default lander is regular")
    };
    let regular_keys = [
        "legs",
        "footpad_radius_m",
        "cg_height_m",
        "first_leg_azimuth_deg",
    ];
    let geometry = match r.take("leg_tips_m") {
        Some(v) => {
            if let Some(k) = regular_keys.iter().find(|k| r.has(k)) {
                return Err(r.error(
                    "leg_tips_m",
                    &v,
                    &format!("either `leg_tips_m` or `{k}` and its fellows, not both"),
                ));
            }
            let allowed = "a non-empty array of footpad positions [[x, y, z], ...] in m";
            let Value::Array(a) = &v else {
                return Err(r.error("leg_tips_m", &v, allowed));
            };
            if a.is_empty() {
                return Err(r.error("leg_tips_m", &v, allowed));
            }
            let tips = a
                .iter()
                .map(|t| r.vec3("leg_tips_m", t))
                .collect::<Result<Vec<_>, _>>()?;
            Geometry::Tips(tips)
        }
        None => Geometry::Regular {
            legs: r.integer("legs", d_legs as i64, 3, 64)? as usize,
            footpad_radius_m: r.positive("footpad_radius_m", d_radius)?,
            cg_height_m: read_parameter(&mut r, Parameter::CgHeightM, d_height, true, sampled)?,
            first_leg_azimuth_deg: r.f64("first_leg_azimuth_deg", d_az)?,
        },
    };
    r.finish()?;
    Ok(Lander {
        mass_kg,
        inertia_kg_m2,
        geometry,
    })
}
