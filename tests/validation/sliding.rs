//! Sliding (MODEL.md sections 5 and 12): the lander holds below the friction limit and
//! slides with the Coulomb acceleration above it.

use super::{Sim, classify, stand};
use crate::common::Table;
use crate::lander::{on_slope, regular, standing};
use touchdown::reference::Outcome;
use touchdown::scenario::Scenario;

#[test]
fn holds_below_friction_limit() {
    holds(
        "sticking: tan(alpha) < mu holds still for 60 s",
        std::convert::identity,
    );
}

/// `holds_below_friction_limit` on the scenarios `with` makes (the step's error control:
/// `step_control.rs`).
pub(super) fn holds(title: &'static str, with: fn(Scenario) -> Scenario) {
    // tan(alpha) < mu: the stick-slip friction must hold the lander. Over 60 s its CG may
    // move by the settling into the normal and tangential springs only: (m g / 4) / k ~
    // 1e-5 m; tolerance 1 mm, which a creep of 17 um/s (the rest threshold's 1/300) would
    // exceed. Slopes up to 0.92 mu, all below the tipping limits.
    let mut table = Table::new(title);
    for (slope, mu, downhill) in [
        (10.0, 0.2, 0.0),
        (20.0, 0.6, 30.0),
        (29.0, 0.6, 0.0),
        (40.0, 0.9, 45.0),
    ] {
        let s = with(standing(regular(4, 0.6, 45.0), mu));
        let (tilt, moved, _) = stand(&s, slope, downhill, 60.0);
        let ratio = slope.to_radians().tan() / mu;
        let case = format!("alpha {slope} mu {mu} (tan a / mu {ratio:.2}) azimuth {downhill}");
        table.at_most(&case, "CG moved in 60 s (m)", moved, 1e-3);
        table.at_most(&case, "tilt change (deg)", tilt, 0.1);
        let summary = classify(&s, on_slope(slope, downhill));
        table.equal(&case, "outcome", summary.outcome, Outcome::Stable);
    }
    table.finish();
}

#[test]
fn slides_with_coulomb_acceleration() {
    slides(
        "sliding: downhill acceleration g0 (sin a - mu cos a)",
        std::convert::identity,
    );
}

/// `slides_with_coulomb_acceleration` on the scenarios `with` makes.
pub(super) fn slides(title: &'static str, with: fn(Scenario) -> Scenario) {
    // tan(alpha) > mu: the CG accelerates down the slope at g0 (sin a - mu cos a), measured
    // from its downhill velocity at 5 s and 30 s (after the stick phase and the settling of
    // the normal springs, which takes ~0.3 s). Tolerance 2 %: in steady sliding every
    // friction force sits at its cap mu F_N and the normal forces sum to m g cos a exactly;
    // what is left is the slow pitch oscillation of the load transfer. Friction up to 0.6:
    // below r/h = 0.99, so the friction moment cannot tip it.
    let mut table = Table::new(title);
    for (slope, mu, downhill) in [
        (20.0, 0.2, 0.0),
        (30.0, 0.3, 20.0),
        (35.0, 0.5, 45.0),
        (40.0, 0.6, 0.0),
    ] {
        let s = with(standing(regular(4, 0.6, 45.0), mu));
        let mut sim = Sim::of(&s, on_slope(slope, downhill));
        sim.advance_to(5.0);
        let v5 = sim.downhill_speed();
        sim.advance_to(30.0);
        let v30 = sim.downhill_speed();
        let a = slope.to_radians();
        let expected = s.gravity_m_s2 * (a.sin() - mu * a.cos());
        let case = format!("alpha {slope} mu {mu} azimuth {downhill}");
        table.relative(
            &case,
            "downhill accel. (m/s^2)",
            (v30 - v5) / 25.0,
            expected,
            0.02,
        );
        table.at_most(&case, "tilt at 30 s (deg)", sim.tilt_deg(), 1.0);
    }
    table.finish();
}
