//! Static tipping on a slope (MODEL.md sections 8 and 12): the closed-form limit of regular
//! gears, and of the default gear.

use super::{classify, stand};
use crate::common::Table;
use crate::lander::{
    CG_HEIGHT_M, FALL_WITHIN_S, Facing, on_slope, regular, standing, tipping_slope_between,
};
use std::f64::consts::PI;
use touchdown::reference::Outcome;

/// The static tipping limit `atan(r / h)` of a regular gear, deg: `r` is the distance from
/// the centre of the support polygon to its boundary along the downhill direction
/// (relative to the lander), `R cos(pi/n) / cos(beta - nearest edge-normal azimuth)`.
fn static_limit_deg(legs: usize, radius_m: f64, first_leg_deg: f64, downhill_deg: f64) -> f64 {
    let sector = 360.0 / legs as f64;
    // Edge normals point at first_leg + sector/2 + k sector.
    let from_normal = (downhill_deg - first_leg_deg - sector / 2.0).rem_euclid(sector);
    let off = from_normal.min(sector - from_normal).to_radians();
    let r = radius_m * (PI / legs as f64).cos() / off.cos();
    (r / CG_HEIGHT_M).atan().to_degrees()
}

/// The first leg's azimuth of the gears of the tipping tests (arbitrary, not 0).
fn first_leg_deg(legs: usize) -> f64 {
    if legs == 4 { 45.0 } else { 30.0 }
}

#[test]
fn static_tipping_limit() {
    // A lander set down aligned with the slope, friction 3 (it cannot slide below 71 deg).
    // 0.5 deg below atan(r/h) it must stay: over 60 s its tilt may change by the contact
    // compliance alone (the static penetration m g / k ~ 1e-5 m over a ~1 m footprint:
    // ~1e-3 deg; tolerance 1 deg) and its CG move by the settling into the springs
    // (~1e-5 m; tolerance 3 mm). 0.5 deg above, it must fall over: tilt past 90 deg within
    // FALL_WITHIN_S. `reference::run` must call the first stable and the second tipped.
    let mut table =
        Table::new("static tipping: stays 0.5 deg below atan(r/h), falls 0.5 deg above");
    for legs in [3, 4] {
        for radius in [0.5, 0.6, 0.9] {
            for facing in [Facing::Side, Facing::Leg, Facing::Between] {
                let phi0 = first_leg_deg(legs);
                let downhill = facing.azimuth_deg(legs, phi0);
                let limit = static_limit_deg(legs, radius, phi0, downhill);
                let mut s = standing(regular(legs, radius, phi0), 3.0);
                s.simulation.t_max_s = 2.0 * FALL_WITHIN_S;
                let case =
                    format!("{legs} legs R {radius} {facing:?} downhill: limit {limit:.2} deg");

                let (tilt, moved, fell) = stand(&s, limit - 0.5, downhill, 60.0);
                table.at_most(&case, "-0.5: tilt change (deg)", tilt, 1.0);
                table.at_most(&case, "-0.5: CG moved (m)", moved, 3e-3);
                table.equal(&case, "-0.5: fell over", fell.is_some(), false);
                let below = classify(&s, on_slope(limit - 0.5, downhill));
                table.equal(&case, "-0.5: outcome", below.outcome, Outcome::Stable);

                let (_, _, fell) = stand(&s, limit + 0.5, downhill, FALL_WITHIN_S);
                table.at_most(
                    &case,
                    "+0.5: time to tilt 90 deg (s)",
                    fell.unwrap_or(f64::INFINITY),
                    FALL_WITHIN_S,
                );
                let above = classify(&s, on_slope(limit + 0.5, downhill));
                table.equal(&case, "+0.5: outcome", above.outcome, Outcome::Tipped);
            }
        }
    }
    table.finish();
}

/// Whether the default gear, set down with contact damping `damping` (normal and
/// tangential), falls over on `slope_deg` at `downhill_deg` within FALL_WITHIN_S.
fn default_gear_falls(damping: f64, slope_deg: f64, downhill_deg: f64) -> bool {
    let mut s = standing(regular(4, 0.6, 45.0), 3.0);
    s.surface.damping_n_s_per_m = damping;
    s.surface.friction_damping_n_s_per_m = damping;
    stand(&s, slope_deg, downhill_deg, FALL_WITHIN_S)
        .2
        .is_some()
}

/// The slope at which the default gear starts to fall over, bracketed by bisection to
/// 1/64 deg between 0.5 deg below and above `limit` (which must bracket it), deg.
fn measured_tipping_slope(damping: f64, limit: f64, downhill_deg: f64) -> f64 {
    tipping_slope_between(limit - 0.5, limit + 0.5, |slope| {
        default_gear_falls(damping, slope, downhill_deg)
    })
}

#[test]
fn static_tipping_default_gear() {
    // MODEL.md section 8: the default gear tips at 44.7 deg with a side downhill and
    // 54.4 deg with a leg downhill. First the formula against those rounded numbers
    // (tolerance 0.05 deg, their rounding). Then the slope at which the lander, set down on
    // it, falls over, found by bisection to 1/64 deg:
    // - set down gently (contact damping 2e4 N s/m per leg, normal and tangential: zeta ~ 9,
    //   overdamped, still stable at 1 ms): within 0.05 deg of atan(r/h) (the static
    //   compliance moves the limit by ~1e-3 deg; a lander 0.01 deg past it takes ~70 s
    //   of the 400 s to fall);
    // - set down with the default contact (zeta 0.49): within 0.25 deg. The springs start
    //   unloaded, and the settling transient rocks the lander; its energy, a fraction of
    //   m g times the static penetration (~1e-5 m), lifts the CG over a barrier of
    //   m g L delta^2 / 2 when the margin delta is below ~0.15 deg.
    let mut table = Table::new("static tipping of the default gear (MODEL.md section 8)");
    for (facing, downhill, quoted) in [("side", 0.0, 44.7), ("leg", 45.0, 54.4)] {
        let limit = static_limit_deg(4, 0.6, 45.0, downhill);
        let case = format!("default gear, {facing} downhill (azimuth {downhill})");
        table.close(&case, "atan(r/h) vs MODEL.md (deg)", limit, quoted, 0.05);
        for (damping, tolerance) in [(2.0e4, 0.05), (1.1e3, 0.25)] {
            for slope in [limit - 0.5, limit + 0.5] {
                let quantity = format!("c {damping:.0}: falls at {:+}", slope - limit);
                table.equal(
                    &case,
                    &quantity,
                    default_gear_falls(damping, slope, downhill),
                    slope > limit,
                );
            }
            let measured = measured_tipping_slope(damping, limit, downhill);
            let quantity = format!("c {damping:.0}: tipping slope (deg)");
            table.close(&case, &quantity, measured, limit, tolerance);
        }
    }
    table.finish();
}
