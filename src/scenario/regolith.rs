//! The `[surface.regolith]` table: the soil a footpad sinks into when `surface.kind` is
//! `"regolith"` (MODEL.md section 5.1). default.toml shows it commented out (a table read
//! only on regolith): the defaults are given here (`Reader::or`), those of a lunar-like
//! soil.

use super::inputs::{Parameter, Sampled, read_parameter};
use super::reader::table;

table! {
    /// A plastic soil: Bekker's pressure-sinkage law on loading, a straight elastic line on
    /// unloading, and the passive earth pressure of Rankine against a sunk footpad's side.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Regolith;
    fn read_regolith(r, sampled: &mut Sampled) with key {
        /// Bekker's cohesive modulus `k_c`, N/m^(n+1): `p = (k_c / b + k_phi) z^n`.
        bekker_k_c: f64 = read_parameter(r.or(key, 1400.0), key, sampled)?,
        /// Bekker's frictional modulus `k_phi`, N/m^(n+2).
        bekker_k_phi: f64 = read_parameter(r.or(key, 820_000.0), key, sampled)?,
        /// Bekker's sinkage exponent `n`.
        bekker_n: f64 = read_parameter(r.or(key, 1.0), key, sampled)?,
        /// The slope of the elastic unloading (and reloading) line, Pa per m of sinkage.
        unloading_modulus_pa_per_m: f64 = read_parameter(r.or(key, 8.0e6), key, sampled)?,
        /// Cohesion `c` of the soil, Pa (the passive earth pressure's cohesive part).
        cohesion_pa: f64 = read_parameter(r.or(key, 170.0), key, sampled)?,
        /// Internal friction angle `phi` of the soil, deg.
        friction_angle_deg: f64 = read_parameter(r.or(key, 35.0), key, sampled)?,
        /// Bulk density of the soil, kg/m^3 (the passive earth pressure's weight part).
        bulk_density_kg_m3: f64 = read_parameter(r.or(key, 1500.0), key, sampled)?,
    }
}

impl Regolith {
    /// The value of a regolith parameter `p` (NaN for the others).
    #[must_use]
    pub fn parameter(&self, p: Parameter) -> f64 {
        use Parameter as P;
        match p {
            P::BekkerKC => self.bekker_k_c,
            P::BekkerKPhi => self.bekker_k_phi,
            P::BekkerN => self.bekker_n,
            P::UnloadingModulusPaPerM => self.unloading_modulus_pa_per_m,
            P::CohesionPa => self.cohesion_pa,
            P::FrictionAngleDeg => self.friction_angle_deg,
            P::BulkDensityKgM3 => self.bulk_density_kg_m3,
            _ => f64::NAN,
        }
    }
}
