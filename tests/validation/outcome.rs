//! Outcome classification (MODEL.md section 8): a gentle drop is stable, a lander upside
//! down is tipped at once, one that never lands is bouncing.

use super::{Sim, classify, moving};
use crate::common::Table;
use crate::lander::{quiet, sample_of};
use glam::DVec3;
use std::f64::consts::PI;
use touchdown::reference::{Model, Outcome, run};
use touchdown::scenario::{AttitudeReference, Inputs, Scenario};

#[test]
fn outcome_gentle_drop_is_stable() {
    // A gentle drop (default surface and gravity) on flat ground or a gentle slope comes to
    // rest: `run` must call it stable, at the time the rest condition (speed, rate, three
    // legs touching or within REST_GAP_M of the surface, every friction anchor within 1
    // micrometre of where it was after the first step of the rest) has held for hold_time_s
    // without a break, within 1.5 steps (the hold is a sum of 1 ms steps). And it must be at rest in fact: stepped on for 30 s more, its
    // CG moves less than 1 mm and its tilt by less than 0.1 deg.
    let mut table = Table::new("outcome: gentle drops end stable");
    for (slope, v0, rates) in [
        (0.0, 0.05, [0.0; 3]),
        (0.0, 0.2, [0.5, -0.5, 0.3]),
        (10.0, 0.1, [0.0; 3]),
        (20.0, 0.15, [0.3, 0.3, 0.0]),
    ] {
        let mut s = Scenario::default();
        s.initial.attitude_reference = AttitudeReference::Surface;
        let inputs = Inputs {
            slope_deg: slope,
            ..moving([0.0, 0.0, -v0], rates)
        };
        let model = Model::new(&s);
        let th = model.thresholds;
        let summary = run(&model, &sample_of(inputs), |_| {});
        let mut rest_since: Option<f64> = None;
        let mut anchors = vec![DVec3::ZERO; model.legs.len()];
        let mut sim = Sim::new(model.clone(), inputs);
        while sim.state.t_s < summary.decided_s - 1e-9 && sim.advance() {
            let r = &sim.report;
            let contacts = r
                .legs
                .iter()
                .filter(|l| l.penetration_m > -kernels::outcome::REST_GAP_M)
                .count();
            let stuck = rest_since.is_none()
                || sim
                    .state
                    .legs
                    .iter()
                    .zip(&anchors)
                    .all(|(l, a)| !l.anchored || l.anchor_m.distance(*a) <= 1e-6);
            let at_rest = r.body.velocity_m_s.length() < th.rest_speed_m_s
                && r.body.rate_rad_s.length() < th.rest_rate_rad_s
                && contacts >= 3
                && stuck;
            if !at_rest {
                rest_since = None;
            } else if rest_since.is_none() {
                rest_since = Some(r.t_s);
                anchors = sim.state.legs.iter().map(|l| l.anchor_m).collect();
            }
        }
        let rest_since = rest_since.unwrap_or(f64::NAN);
        let case = format!("slope {slope} v0 {v0} rates {rates:?}");
        table.equal(&case, "outcome", summary.outcome, Outcome::Stable);
        table.close(
            &case,
            "decided at (s)",
            summary.decided_s,
            rest_since + th.hold_time_s,
            1.5 * model.step_s,
        );

        let mut after = Sim::of(&s, inputs);
        after.model.t_max_s = summary.decided_s + 30.0;
        after.advance_to(summary.decided_s);
        let (x, tilt) = (after.state.body.position_m, after.tilt_deg());
        after.advance_to(summary.decided_s + 30.0);
        table.at_most(
            &case,
            "CG moved in 30 s after (m)",
            (after.state.body.position_m - x).length(),
            1e-3,
        );
        table.at_most(
            &case,
            "tilt change after (deg)",
            (after.tilt_deg() - tilt).abs(),
            0.1,
        );
    }
    table.finish();
}

#[test]
fn outcome_upside_down_is_tipped_at_once() {
    // Tilt from the surface normal beyond 90 deg counts as tipped at once, in flight too:
    // decided on the first step. The tilt of roll phi and pitch theta (yaw 0, against the
    // surface normal) has cos(tilt) = cos(phi) cos(theta). Tilts below 90 deg are the
    // control: not tipped (in flight, 100 m up, they end bouncing at t_max).
    let mut table = Table::new("outcome: tilted past 90 deg is tipped at once");
    let attitudes = [
        (180.0, 0.0, 0.0),
        (95.0, 0.0, 0.0),
        (0.0, 120.0, 0.0),
        (-100.0, 30.0, 0.0),
        (0.0, 95.0, 30.0),
        (80.0, 0.0, 0.0),
        (60.0, -60.0, 20.0),
    ];
    for (roll, pitch, slope) in attitudes {
        let mut s = Scenario::default();
        s.initial.attitude_reference = AttitudeReference::Surface;
        s.initial.clearance_m = 100.0;
        s.simulation.t_max_s = 10.0;
        let inputs = Inputs {
            roll_deg: roll,
            pitch_deg: pitch,
            slope_deg: slope,
            ..quiet()
        };
        let summary = classify(&s, inputs);
        let tilt = (roll.to_radians().cos() * pitch.to_radians().cos()).acos();
        let case = format!(
            "roll {roll} pitch {pitch} (tilt {:.1}) on slope {slope}",
            tilt.to_degrees()
        );
        if tilt > PI / 2.0 {
            table.equal(&case, "outcome", summary.outcome, Outcome::Tipped);
            table.equal(&case, "steps to decide", summary.steps, 1);
        } else {
            table.equal(&case, "outcome", summary.outcome, Outcome::Bouncing);
        }
    }
    table.finish();
}

#[test]
fn outcome_never_landing_is_bouncing() {
    // A lander that is airborne at t_max is bouncing, whether it never touched (moving up
    // in weak gravity, or sideways in none) or is in the air after a rebound (elastic
    // surface, default gravity: airborne for 2 v_out / g0 ~ 60 s after a 0.5 m/s drop).
    let mut table = Table::new("outcome: airborne at t_max is bouncing");
    let cases: [(&str, f64, f64, [f64; 3], f64); 4] = [
        ("rising, g0 1e-4", 1e-4, 0.01, [0.0, 0.0, 0.1], 0.0),
        ("rising, g0 1e-3", 1e-3, 0.5, [0.05, 0.0, 0.2], 1100.0),
        ("sideways, g0 0", 0.0, 0.5, [0.3, -0.2, 0.0], 1100.0),
        (
            "rebounding, elastic surface",
            0.0168,
            0.001,
            [0.0, 0.0, -0.5],
            0.0,
        ),
    ];
    for (name, g0, clearance, velocity, damping) in cases {
        let mut s = Scenario {
            gravity_m_s2: g0,
            ..Scenario::default()
        };
        s.initial.clearance_m = clearance;
        s.surface.damping_n_s_per_m = damping;
        s.simulation.t_max_s = 30.0;
        // Run to t_max, and with the early `bouncing` rule (MODEL.md section 8): the same
        // outcome, decided as soon as the flight cannot end before t_max (all four can't:
        // rising faster than g0 t_max / 2 from above the legs' reach, no gravity, or an
        // elastic rebound into a 60 s flight), after the first contact where there is one.
        s.outcome.early_bouncing = false;
        let summary = classify(&s, moving(velocity, [0.0; 3]));
        s.outcome.early_bouncing = true;
        let early = classify(&s, moving(velocity, [0.0; 3]));
        table.equal(name, "outcome", summary.outcome, Outcome::Bouncing);
        table.close(name, "decided at (s)", summary.decided_s, 30.0, 1e-9);
        table.equal(
            name,
            "touched the surface",
            summary.first_contact_s.is_some(),
            velocity[2] < 0.0,
        );
        table.equal(
            name,
            "outcome, early rule",
            early.outcome,
            Outcome::Bouncing,
        );
        table.equal(
            name,
            "decided before t_max, after any contact",
            early.decided_s < 30.0 && early.first_contact_s.is_none_or(|t| t < early.decided_s),
            true,
        );
    }
    table.finish();
}
