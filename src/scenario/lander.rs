//! The `[lander]` table: the lander's mass, inertia and leg geometry.

use super::error::ScenarioError;
use super::inputs::{Sampled, read_parameter};
use super::reader::{Reader, table};
use toml::Value;

/// Where the lander's legs are.
#[derive(Debug, Clone, PartialEq)]
pub enum Geometry {
    /// `legs` footpads evenly spaced on a circle of `footpad_radius_m` around Z_B,
    /// `cg_height_m` below the CG, the first at `first_leg_azimuth_deg` from X_B.
    Regular {
        /// Number of legs.
        legs: usize,
        /// Radius of the footpads' circle around Z_B, m.
        footpad_radius_m: f64,
        /// Height of the CG above the footpads, m.
        cg_height_m: f64,
        /// Azimuth of the first leg from X_B, deg.
        first_leg_azimuth_deg: f64,
    },
    /// Explicit footpad positions in B, m.
    Tips(Vec<[f64; 3]>),
}

table! {
    /// The lander (MODEL.md section 3).
    #[derive(Debug, Clone, PartialEq)]
    pub struct Lander;
    fn read_lander(r, sampled: &mut Sampled) with key {
        /// Mass.
        mass_kg: f64 = read_parameter(r, key, sampled)?,
        /// Principal moments of inertia about X_B, Y_B, Z_B.
        inertia_kg_m2: [f64; 3] = read_inertia(r, key)?,
        /// Where the legs are: `legs` and its fellows, or `leg_tips_m`.
        geometry: Geometry = read_geometry(r, sampled)?,
        /// Area of each footpad's sole, m^2: its bearing area on regolith, and the size of
        /// the sphere that meets rocks (MODEL.md section 5.1). default.toml shows it
        /// commented out, with this default.
        footpad_area_m2: f64 = read_parameter(r.or(key, 0.03), key, sampled)?,
    }
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

fn read_inertia(r: &mut Reader, key: &'static str) -> Result<[f64; 3], ScenarioError> {
    let v = r.value(key)?;
    let i = r.vec3(key, &v)?;
    if i.iter().any(|x| *x <= 0.0) {
        return Err(r.error(key, &v, "three principal moments greater than 0"));
    }
    // A rigid body's principal moments obey the triangle inequality; equality is a flat
    // plate. The relative slack absorbs rounding in values typed from decimals.
    for k in 0..3 {
        let (a, b, c) = (i[k], i[(k + 1) % 3], i[(k + 2) % 3]);
        if a > (b + c) * (1.0 + 1e-12) {
            return Err(r.error(
                key,
                &v,
                "principal moments of a rigid body: each at most the sum of the other two (triangle inequality)",
            ));
        }
    }
    Ok(i)
}

/// The legs: `leg_tips_m`, or the regular keys in its place.
fn read_geometry(r: &mut Reader, sampled: &mut Sampled) -> Result<Geometry, ScenarioError> {
    let regular_keys = [
        "legs",
        "footpad_radius_m",
        "cg_height_m",
        "first_leg_azimuth_deg",
    ];
    let Some(v) = r.take("leg_tips_m") else {
        return Ok(Geometry::Regular {
            legs: r.integer("legs", 3, 64)?,
            footpad_radius_m: r.positive("footpad_radius_m")?,
            cg_height_m: read_parameter(r, "cg_height_m", sampled)?,
            first_leg_azimuth_deg: r.f64("first_leg_azimuth_deg")?,
        });
    };
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
    Ok(Geometry::Tips(tips))
}
