//! Static tipping limit under hold-down thrust: the thrust raises it to the closed form
//! `thrust_limit_deg`.

use super::{Sim, constant_thrust};
use crate::common::Table;
use crate::lander::{FALL_WITHIN_S, Facing, on_slope, regular, standing, tipping_slope_between};
use glam::DVec3;
use touchdown::scenario::Scenario;

/// The slope at which a gear pushed by `thrust` along -Z_B through the CG tips: about the
/// downhill edge, weight (m g0 at height h above the footpad plane, r behind the edge)
/// tips it while m g0 (h sin a - r cos a) exceeds F r, i.e. a = atan(r / h) + asin(F r /
/// (m g0 L)), L = sqrt(h^2 + r^2). `r` and `h` from `stability::static_limit_deg` (the
/// passive limit atan(r / h)), deg.
fn thrust_limit_deg(scenario: &Scenario, downhill_deg: f64, thrust: f64) -> (f64, f64) {
    let tips = scenario.lander.tips_m();
    let passive = touchdown::stability::static_limit_deg(&tips, downhill_deg).expect("stands");
    let h = -tips[0][2];
    let r = h * passive.to_radians().tan();
    let weight = scenario.lander.mass_kg * scenario.gravity_m_s2;
    let lift = (thrust * r / (weight * h.hypot(r))).asin();
    (passive, passive + lift.to_degrees())
}

/// Sets the gear of `scenario` on `slope_deg` at `downhill_deg` with `thrust` along -Z_B
/// from the start and steps it for `duration_s` or until its tilt from the normal passes
/// 90 deg; returns (largest tilt change, deg; largest CG displacement, m; time its tilt
/// passed 90 deg).
fn stand(
    scenario: &Scenario,
    slope_deg: f64,
    downhill_deg: f64,
    thrust: f64,
    duration_s: f64,
) -> (f64, f64, Option<f64>) {
    let mut sim = Sim::of(scenario, on_slope(slope_deg, downhill_deg));
    sim.state.thrust = constant_thrust(DVec3::new(0.0, 0.0, -thrust), DVec3::ZERO);
    let (tilt0, x0) = (sim.tilt_deg(), sim.state.body.position_m);
    let (mut tilt, mut moved) = (0.0f64, 0.0f64);
    while sim.state.t_s < duration_s - 1e-9 {
        sim.advance();
        tilt = tilt.max((sim.tilt_deg() - tilt0).abs());
        moved = moved.max((sim.state.body.position_m - x0).length());
        if sim.tilt_deg() > 90.0 {
            return (tilt, moved, Some(sim.state.t_s));
        }
    }
    (tilt, moved, None)
}

/// The gear set down gently: contact damping 2e4 N s/m per leg, normal and tangential
/// (overdamped, still stable at 1 ms), friction 3 (no sliding below 71 deg, nor with the
/// thrust's friction cap, below the 85 deg of these cases).
fn gently(legs: usize, footpad_radius_m: f64, first_leg_deg: f64) -> Scenario {
    let mut s = standing(regular(legs, footpad_radius_m, first_leg_deg), 3.0);
    s.surface.damping_n_s_per_m = 2.0e4;
    s.surface.friction_damping_n_s_per_m = 2.0e4;
    s.simulation.t_max_s = 2.0 * FALL_WITHIN_S;
    s
}

/// Bisects, to 1/64 deg, the slope between `stays` and `falls` at which the gear of
/// `scenario` with `thrust` falls over within FALL_WITHIN_S.
fn tipping_slope(scenario: &Scenario, downhill: f64, thrust: f64, stays: f64, falls: f64) -> f64 {
    tipping_slope_between(stays, falls, |slope| {
        stand(scenario, slope, downhill, thrust, FALL_WITHIN_S)
            .2
            .is_some()
    })
}

#[test]
fn thrust_raises_the_static_tipping_limit() {
    // A gear set down gently, aligned with the slope, with a thrust F along -Z_B through
    // the CG from the start: it tips at a = atan(r/h) + asin(F r / (m g0 L))
    // (`thrust_limit_deg`; g0 = 0.0168, m g0 = 1.68 N, so 0.25-1 N moves the limit by
    // 6-29 deg). As the passive test (validation::tipping): 0.5 deg below, over 60 s its
    // tilt may change by the contact compliance alone ((m g0 + F) / (4 k) ~ 1e-5 m over a
    // ~1 m footprint: ~1e-3 deg; tolerance 1 deg) and its CG move by the settling into the
    // springs (tolerance 3 mm); 0.5 deg above, it must fall over (tilt past 90 deg) within
    // FALL_WITHIN_S. Past the limit the thrust's moment about the edge stays F r (it turns
    // with the body) while the weight's grows with the tilt, up to m g0 L, which exceeds
    // F r by a factor (m g0 L) / (F r) >= 2 here: nothing holds it before
    // 90 deg. Four- and three-leg gears, a side and a leg facing downhill, F 0.25, 0.5, 1
    // N. For the default gear at 0.5 N the limit is also found by bisection to 1/64 deg:
    // within 0.05 deg, as the passive gentle test (the compliance moves it by ~1e-3 deg, and
    // a lander 0.01 deg past it takes ~70 s of the 400 s to fall).
    let mut table = Table::new("thrust: static tipping limit under hold-down thrust");
    for (legs, radius, first) in [(4, 0.6, 45.0), (3, 0.6, 30.0)] {
        for facing in [Facing::Side, Facing::Leg] {
            let s = gently(legs, radius, first);
            let downhill = facing.azimuth_deg(legs, first);
            for thrust in [0.25, 0.5, 1.0] {
                let (passive, limit) = thrust_limit_deg(&s, downhill, thrust);
                let case = format!(
                    "{legs} legs R {radius} {facing:?} downhill, F {thrust} N: \
                     {passive:.2} -> {limit:.2} deg"
                );
                let (tilt, moved, fell) = stand(&s, limit - 0.5, downhill, thrust, 60.0);
                table.at_most(&case, "-0.5: tilt change in 60 s (deg)", tilt, 1.0);
                table.at_most(&case, "-0.5: CG moved in 60 s (m)", moved, 3e-3);
                table.equal(&case, "-0.5: fell over", fell.is_some(), false);
                let (_, _, fell) = stand(&s, limit + 0.5, downhill, thrust, FALL_WITHIN_S);
                table.at_most(
                    &case,
                    "+0.5: time to tilt 90 deg (s)",
                    fell.unwrap_or(f64::INFINITY),
                    FALL_WITHIN_S,
                );
                if legs == 4 && thrust == 0.5 {
                    let measured = tipping_slope(&s, downhill, thrust, limit - 0.5, limit + 0.5);
                    table.close(&case, "tipping slope (deg)", measured, limit, 0.05);
                }
            }
        }
    }
    table.finish();
}
