//! Hold-down at rest: the legs bear the weight's normal component plus the thrust.

use super::{Sim, constant_thrust};
use crate::common::Table;
use crate::lander::{on_slope, regular, standing};
use glam::DVec3;

/// Settling time before each measurement of the hold-down test, s.
const SETTLE_S: f64 = 10.0;

#[test]
fn thrust_hold_down_adds_to_the_normal_force() {
    // The default lander set down aligned with a plane (flat, 10 and 20 deg, mu 0.6: below
    // the friction angle of 31 deg and the tipping limits of 44.7 deg and more) settles for
    // 10 s; then a thrust F along -Z_B through the CG (Z_B along the normal, to the
    // settling's 1e-3 deg) pushes it for 10 s more. At rest the sum of the legs' normal
    // forces balances the normal components of weight and thrust: m g0 cos(a) + F
    // (before the thrust, m g0 cos(a)). Newton's law along the normal says the residual is
    // m times the CG's normal acceleration (plus F (1 - cos tilt), 1e-10 F): what is left
    // of the settling transient. Its slowest mode, the stick-slip friction springs on the
    // yaw and sway axes (4 k_f r^2 = 7.2e4 N m/rad against I_z = 15 kg m^2, damped by
    // 4 c_f r^2 = 1.6e3 N m s/rad: a time constant below 0.02 s), is below 1e-100 of the
    // load after 10 s, so only rounding is left (sums of four forces of up to 11 N: 1e-14
    // N). Tolerance 1e-9 relative to the load, with margin for rounding-level limit cycles
    // of the stick-slip spring. A thrust lost, doubled or tilted by 1 deg would be off by
    // 5 N, 2e-4 N and more.
    let mut table = Table::new("thrust: hold-down at rest, sum of normal forces");
    for (slope, downhill) in [(0.0, 0.0), (10.0, 0.0), (10.0, 45.0), (20.0, 30.0)] {
        for thrust in [5.0, 20.0, 40.0] {
            let s = standing(regular(4, 0.6, 45.0), 0.6);
            let mut sim = Sim::of(&s, on_slope(slope, downhill));
            let (m, g0) = (sim.model.mass_kg, sim.model.gravity_m_s2);
            let weight = m * g0 * slope.to_radians().cos();
            let case = format!("slope {slope} azimuth {downhill}, F {thrust} N");
            sim.advance_to(SETTLE_S);
            table.relative(
                &case,
                "passive: sum N (N)",
                sim.normal_force_n(),
                weight,
                1e-9,
            );
            let (x0, tilt0) = (sim.state.body.position_m, sim.tilt_deg());
            sim.state.thrust = constant_thrust(DVec3::new(0.0, 0.0, -thrust), DVec3::ZERO);
            sim.state.thrust.powered = false;
            sim.advance_to(2.0 * SETTLE_S);
            let mut worst: f64 = 0.0;
            let end = 2.0 * SETTLE_S + 1.0;
            while sim.state.t_s < end - 1e-9 {
                sim.advance();
                worst = worst.max((sim.normal_force_n() / (weight + thrust) - 1.0).abs());
            }
            table.relative(
                &case,
                "thrust: sum N (N)",
                sim.normal_force_n(),
                weight + thrust,
                1e-9,
            );
            table.at_most(&case, "thrust: max rel. error, last 1 s", worst, 1e-9);
            // Stuck in place: the thrust only presses the springs (F / (4 k) = 0.2 mm at
            // 40 N on flat ground), and no leg slides. Tolerance 1 mm, tilt 0.1 deg.
            let moved = (sim.state.body.position_m - x0).length();
            table.at_most(&case, "CG moved under thrust (m)", moved, 1e-3);
            table.at_most(
                &case,
                "tilt change under thrust (deg)",
                (sim.tilt_deg() - tilt0).abs(),
                0.1,
            );
            table.equal(
                &case,
                "a leg slips",
                sim.report.legs.iter().any(|l| l.slipping),
                false,
            );
        }
    }
    table.finish();
}
