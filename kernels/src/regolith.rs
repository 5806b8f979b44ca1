//! Regolith that gives way, over lanes: the same law as the reference's `regolith`, in the
//! same order, with `select` where the reference branches (MODEL.md section 5.1).

use crate::lane::{Lane, Mask};
use crate::params::SoilParams;
use crate::vec3::Vec3;

/// The soil's push on each footpad `penetration` below the surface, before damping (the
/// lanes where `contact` is false give what they give: the caller drops them): on the
/// loading curve beyond the deepest sinkage so far (which it deepens), else on the
/// unloading line through it (`unloading_slope`), never pulling. Updates the footprint.
/// The power is taken lane by lane (`libm::pow`, as the reference), only in lanes on the
/// loading curve and only in a step where some lane is: a footpad at rest is on its
/// unloading line.
#[inline(always)]
pub fn soil_force<L: Lane>(
    soil: &SoilParams<L>,
    contact: L::Mask,
    penetration: L,
    sinkage_max_m: &mut L,
    soil_force_max_n: &mut L,
) -> L {
    let unloading = unloading_slope_lanes(soil, *sinkage_max_m, *soil_force_max_n)
        .mul_neg_add(*sinkage_max_m - penetration, *soil_force_max_n)
        .max(L::splat(0.0));
    let loading = penetration.simd_gt(*sinkage_max_m) & contact;
    let bits = loading.to_bitmask();
    if bits == 0 {
        return unloading;
    }
    let mut power = L::splat(0.0);
    for i in 0..L::LANES {
        if bits & (1 << i) != 0 {
            power.set_lane(i, libm::pow(penetration.lane(i), soil.exponent.lane(i)));
        }
    }
    let f = soil.virgin_n * power;
    *sinkage_max_m = loading.select(penetration, *sinkage_max_m);
    *soil_force_max_n = loading.select(f, *soil_force_max_n);
    loading.select(f, unloading)
}

/// `unloading_slope` of each lane (where no footprint is pressed yet, `z_m = 0`, the
/// soil's `A k_u`).
#[inline(always)]
fn unloading_slope_lanes<L: Lane>(
    soil: &SoilParams<L>,
    sinkage_max_m: L,
    soil_force_max_n: L,
) -> L {
    let floor = soil.exponent.max(L::splat(1.0)) * soil_force_max_n / sinkage_max_m;
    sinkage_max_m
        .simd_gt(L::splat(0.0))
        .select(soil.unloading_n_per_m.max(floor), soil.unloading_n_per_m)
}

/// The passive earth pressure on the side of each footpad `penetration` below the surface
/// (Rankine, over the footpad's width), N.
#[inline(always)]
#[must_use]
pub fn passive_force<L: Lane>(soil: &SoilParams<L>, penetration: L) -> L {
    let d = penetration.max(L::splat(0.0));
    d * soil
        .passive_quadratic_n_per_m2
        .mul_add(d, soil.passive_linear_n_per_m)
}

/// In the lanes of `touches_down`, at a touchdown `offset` (in I) from where the leg's
/// friction anchor last was: a footpad that lands farther than its radius from its
/// footprint (measured across the `normal`) presses virgin soil, and the footprint it leaves
/// adds its energy to `soil_absorbed_j` (`absorbed`, lane by lane: touchdowns are rare).
#[inline(always)]
pub fn footprint<L: Lane>(
    soil: &SoilParams<L>,
    touches_down: L::Mask,
    offset: Vec3<L>,
    normal: Vec3<L>,
    sinkage_max_m: &mut L,
    soil_force_max_n: &mut L,
    soil_absorbed_j: &mut L,
) {
    let across = normal.mul_neg_add(normal.dot(offset), offset);
    let elsewhere = across
        .length_squared()
        .simd_gt(soil.pad_radius_m * soil.pad_radius_m)
        & touches_down;
    let bits = elsewhere.to_bitmask();
    if bits == 0 {
        return;
    }
    for i in 0..L::LANES {
        if bits & (1 << i) != 0 {
            let left = absorbed(
                soil.exponent.lane(i),
                soil.unloading_n_per_m.lane(i),
                sinkage_max_m.lane(i),
                soil_force_max_n.lane(i),
            );
            soil_absorbed_j.set_lane(i, soil_absorbed_j.lane(i) + left);
        }
    }
    let zero = L::splat(0.0);
    *sinkage_max_m = elsewhere.select(zero, *sinkage_max_m);
    *soil_force_max_n = elsewhere.select(zero, *soil_force_max_n);
}

/// The slope of the unloading line through a footprint's deepest point `(z_m, F_m)`, N/m
/// (of one lane; the kernels take it lane by lane, in the same order): the soil's
/// `A k_u`, but never less than `max(1, n) F_m / z_m`, the loading curve's chord to the
/// deepest point (`n <= 1`) or its tangent there (`n > 1`), whichever is steeper. The line
/// then never rises above the loading curve, so the soil never gives back more work than
/// the loading took, for any `n` and `k_u` (MODEL.md section 5.1); where `A k_u` is the
/// steeper, it is the line as the soil's modulus gives it. `A k_u` where no footprint is
/// pressed yet (`z_m = 0`).
#[must_use]
pub fn unloading_slope(
    exponent: f64,
    unloading_n_per_m: f64,
    sinkage_max_m: f64,
    soil_force_max_n: f64,
) -> f64 {
    if sinkage_max_m > 0.0 {
        unloading_n_per_m.max(exponent.max(1.0) * soil_force_max_n / sinkage_max_m)
    } else {
        unloading_n_per_m
    }
}

/// The depth of a footprint of deepest sinkage `z_m` (force `F_m`) once the footpad has
/// lifted: where the unloading line (`unloading_slope`) meets zero force, at or below the
/// surface, m. (Of one lane, outside the step: the reference's `permanent_sinkage`.)
#[must_use]
pub fn permanent_sinkage(
    exponent: f64,
    unloading_n_per_m: f64,
    sinkage_max_m: f64,
    soil_force_max_n: f64,
) -> f64 {
    let slope = unloading_slope(exponent, unloading_n_per_m, sinkage_max_m, soil_force_max_n);
    (sinkage_max_m - soil_force_max_n / slope).max(0.0)
}

/// The energy a footprint of deepest sinkage `z_m` (force `F_m`) took for good: the work
/// along the loading curve, `F_m z_m / (n + 1)`, less what the unloading line gives back,
/// `F_m (z_m - z_p) / 2`, never negative (`unloading_slope`), J (of one lane: the
/// reference's `absorbed`).
#[must_use]
pub fn absorbed(
    exponent: f64,
    unloading_n_per_m: f64,
    sinkage_max_m: f64,
    soil_force_max_n: f64,
) -> f64 {
    let loading = soil_force_max_n * sinkage_max_m / (exponent + 1.0);
    let z_p = permanent_sinkage(exponent, unloading_n_per_m, sinkage_max_m, soil_force_max_n);
    let given_back = 0.5 * soil_force_max_n * (sinkage_max_m - z_p);
    loading - given_back
}

/// A leg's regolith results at the end of a sample (of one lane): the depth of its last
/// footprint (`permanent_sinkage`) and the energy all its footprints absorbed (the earlier
/// ones' `soil_absorbed_j` and the last one's `absorbed`).
#[must_use]
pub fn leg_results(
    exponent: f64,
    unloading_n_per_m: f64,
    sinkage_max_m: f64,
    soil_force_max_n: f64,
    soil_absorbed_j: f64,
) -> (f64, f64) {
    (
        permanent_sinkage(exponent, unloading_n_per_m, sinkage_max_m, soil_force_max_n),
        soil_absorbed_j + absorbed(exponent, unloading_n_per_m, sinkage_max_m, soil_force_max_n),
    )
}
