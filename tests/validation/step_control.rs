//! The error control of the contact step (MODEL.md section 2.1): with a tolerance, the
//! bounce and the slide keep their closed forms as a fixed step that resolves the contact
//! does, and a lander below the friction limit still holds still.

use super::restitution::{measured_restitution, restitution};
use super::sliding::{holds, slides};
use crate::common::Table;
use touchdown::scenario::{Geometry, Scenario};

/// The tolerance of these checks, m/s: the one the README and MODEL.md recommend.
const TOLERANCE_M_S: f64 = 1e-4;

/// `scenario` with the error control at `tolerance` and its default bounds (`step_s` 1 ms:
/// contact steps from 0.125 to 2 ms).
fn controlled_at(mut scenario: Scenario, tolerance: f64) -> Scenario {
    scenario.simulation.tolerance_m_s = Some(tolerance);
    scenario
}

/// `controlled_at` the recommended `TOLERANCE_M_S`.
fn controlled(scenario: Scenario) -> Scenario {
    controlled_at(scenario, TOLERANCE_M_S)
}

#[test]
fn restitution_under_the_error_control() {
    // One footpad under the CG dropped from 5 cm in zero gravity, in free flight at long
    // steps: the flight steps shrink onto the contact (within `step_min_s` of it) and the
    // contact steps follow the error estimate. Tolerance 2 %, the requirement, which a fixed
    // step meets only where it resolves the contact (0.25 ms here; at 1 ms the onset phase
    // adds up to 2 zeta omega dt: `restitution.rs`). The tolerance is a velocity: the
    // relative error of a bounce follows the tolerance over the impact speed, so the slow
    // drop (0.05 m/s) runs at a tolerance as much smaller (1e-5 m/s; at 1e-4 m/s two of its
    // cases err by 2.04 % and 2.25 %).
    let mut table = Table::new("restitution, one footpad, error control");
    for (stiffness, mass) in [
        (5.0e4, 100.0),
        (2.0e5, 100.0),
        (1.0e4, 50.0),
        (3.0e5, 100.0),
    ] {
        for zeta in [0.05, 0.2, 0.5, 0.8] {
            for (v0, tolerance) in [(0.05, 1e-5), (0.2, TOLERANCE_M_S), (0.6, TOLERANCE_M_S)] {
                let mut s = controlled_at(Scenario::default(), tolerance);
                s.lander.geometry = Geometry::Tips(vec![[0.0, 0.0, -0.4]]);
                s.lander.mass_kg = mass;
                s.surface.stiffness_n_per_m = stiffness;
                s.surface.damping_n_s_per_m = 2.0 * zeta * (stiffness * mass).sqrt();
                s.gravity_m_s2 = 0.0;
                s.initial.clearance_m = 0.05;
                let case =
                    format!("k {stiffness:.0e} m {mass} zeta {zeta} v0 {v0} tol {tolerance}");
                let e = measured_restitution(&s, v0);
                table.relative(&case, "e = v_out / v_in", e, restitution(zeta), 0.02);
            }
        }
    }
    table.finish();
}

#[test]
fn holds_below_the_friction_limit_under_the_error_control() {
    // `sliding.rs`'s check with the error control, whose quiet contact steps are its
    // longest (2 ms): over 60 s the CG moves by the settling into the springs only (~1e-5
    // m); tolerance 1 mm, which a creep of 17 um/s would exceed; and the outcome is stable.
    holds(
        "sticking under the error control: tan(alpha) < mu",
        controlled,
    );
}

#[test]
fn slides_with_coulomb_acceleration_under_the_error_control() {
    // `sliding.rs`'s check with the error control: the downhill acceleration g0 (sin a - mu
    // cos a) from the downhill speed at 5 s and 30 s, within 2 % (the same argument).
    slides(
        "sliding under the error control: g0 (sin a - mu cos a)",
        controlled,
    );
}
