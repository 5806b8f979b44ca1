//! Regolith that gives way (MODEL.md section 5.1): a footpad sinks plastically along
//! Bekker's pressure-sinkage curve, springs back along a straight unloading line, keeps the
//! footprint it pressed, and meets the passive earth pressure of the soil in front of it
//! when it slides. The kernels' `regolith` does the same, in the same order.
//!
//! A leg remembers its footprint in three numbers (in `contact::LegState`): the deepest
//! sinkage `z_m` and the force `F_m` it reached there (on the loading curve), and the
//! energy the footprints it left before absorbed.

use crate::scenario::Regolith;
use glam::DVec3;

/// The soil under one footpad, in the forces the step needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Soil {
    /// `A (k_c / b + k_phi)`, N/m^n: the loading curve is `F = virgin_n z^n`.
    pub virgin_n: f64,
    /// Bekker's exponent `n`.
    pub exponent: f64,
    /// `A k_u`: the stiffness of the unloading line, N/m.
    pub unloading_n_per_m: f64,
    /// `2 D c sqrt(K_p)`: the passive earth pressure's cohesive part per depth, N/m.
    pub passive_linear_n_per_m: f64,
    /// `D gamma K_p / 2`: its weight part per squared depth, N/m^2.
    pub passive_quadratic_n_per_m2: f64,
    /// The footpad's radius `b = sqrt(A / pi)`: a footpad that touches down farther than
    /// this from where it lifted off presses virgin soil.
    pub pad_radius_m: f64,
}

impl Soil {
    /// The soil of `regolith` under a footpad of `area_m2`, in `gravity_m_s2`.
    #[must_use]
    pub fn of(regolith: &Regolith, area_m2: f64, gravity_m_s2: f64) -> Soil {
        let b = (area_m2 / std::f64::consts::PI).sqrt();
        let sin_phi = libm::sin(regolith.friction_angle_deg.to_radians());
        // Rankine: K_p = tan^2(45 deg + phi / 2) = (1 + sin phi) / (1 - sin phi).
        let k_p = (1.0 + sin_phi) / (1.0 - sin_phi);
        let width_m = 2.0 * b;
        let unit_weight = regolith.bulk_density_kg_m3 * gravity_m_s2;
        Soil {
            virgin_n: area_m2 * (regolith.bekker_k_c / b + regolith.bekker_k_phi),
            exponent: regolith.bekker_n,
            unloading_n_per_m: area_m2 * regolith.unloading_modulus_pa_per_m,
            passive_linear_n_per_m: 2.0 * width_m * regolith.cohesion_pa * k_p.sqrt(),
            passive_quadratic_n_per_m2: 0.5 * width_m * unit_weight * k_p,
            pad_radius_m: b,
        }
    }
}

/// The soil's push on a footpad `penetration > 0` below the surface, before damping: on
/// the loading curve beyond the deepest sinkage so far (which it deepens), else on the
/// unloading line through it (`unloading_slope`), never pulling. Updates the footprint.
#[inline]
pub fn soil_force(
    soil: &Soil,
    penetration: f64,
    sinkage_max_m: &mut f64,
    soil_force_max_n: &mut f64,
) -> f64 {
    if penetration > *sinkage_max_m {
        let f = soil.virgin_n * libm::pow(penetration, soil.exponent);
        *sinkage_max_m = penetration;
        *soil_force_max_n = f;
        f
    } else {
        let slope = unloading_slope(soil, *sinkage_max_m, *soil_force_max_n);
        (*soil_force_max_n - slope * (*sinkage_max_m - penetration)).max(0.0)
    }
}

/// The slope of the unloading line through the deepest point `(z_m, F_m)`, N/m: `A k_u`,
/// but never less than `max(1, n) F_m / z_m` (the loading curve's chord, or for `n > 1`
/// its tangent, at the deepest point), so that the line never rises above the loading
/// curve and the soil never gives back more than it took (MODEL.md section 5.1).
#[must_use]
pub fn unloading_slope(soil: &Soil, sinkage_max_m: f64, soil_force_max_n: f64) -> f64 {
    kernels::regolith::unloading_slope(
        soil.exponent,
        soil.unloading_n_per_m,
        sinkage_max_m,
        soil_force_max_n,
    )
}

/// The passive earth pressure on the side of a footpad `penetration` below the surface
/// (Rankine, over the footpad's width): what the soil in front of it resists a slide with,
/// beyond the friction of its sole, N.
#[inline]
#[must_use]
pub fn passive_force(soil: &Soil, penetration: f64) -> f64 {
    let d = penetration.max(0.0);
    d * (soil.passive_linear_n_per_m + soil.passive_quadratic_n_per_m2 * d)
}

/// At a touchdown `offset` (in I) from where the leg's friction anchor last was: a
/// footpad that lands farther than its radius from its footprint (measured across the
/// `normal`) presses virgin soil, and the footprint it leaves adds its energy to
/// `soil_absorbed_j`.
#[inline]
pub fn footprint(
    soil: &Soil,
    offset: DVec3,
    normal: DVec3,
    sinkage_max_m: &mut f64,
    soil_force_max_n: &mut f64,
    soil_absorbed_j: &mut f64,
) {
    let across = offset - normal * normal.dot(offset);
    if across.length_squared() > soil.pad_radius_m * soil.pad_radius_m {
        *soil_absorbed_j += absorbed(soil, *sinkage_max_m, *soil_force_max_n);
        *sinkage_max_m = 0.0;
        *soil_force_max_n = 0.0;
    }
}

/// The depth of the footprint once the footpad has lifted: where the unloading line from
/// `(z_m, F_m)` meets zero force, at or below the surface, m.
#[must_use]
pub fn permanent_sinkage(soil: &Soil, sinkage_max_m: f64, soil_force_max_n: f64) -> f64 {
    kernels::regolith::permanent_sinkage(
        soil.exponent,
        soil.unloading_n_per_m,
        sinkage_max_m,
        soil_force_max_n,
    )
}

/// The energy a footprint of deepest sinkage `z_m` (force `F_m`) took from the lander for
/// good: the work along the loading curve, `F_m z_m / (n + 1)`, less what the unloading line
/// gives back (the triangle `F_m (z_m - z_p) / 2`), never negative, J.
#[must_use]
pub fn absorbed(soil: &Soil, sinkage_max_m: f64, soil_force_max_n: f64) -> f64 {
    kernels::regolith::absorbed(
        soil.exponent,
        soil.unloading_n_per_m,
        sinkage_max_m,
        soil_force_max_n,
    )
}
