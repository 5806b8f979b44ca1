//! The loop as a user meets it in `scenarios/hold-down.toml`: a torque asked for in the
//! fall pushes the lander nowhere, and a touchdown switch that closes between two control
//! instants is seen at the next.

use crate::common::Table;
use touchdown::reference::{Model, StepReport, run};
use touchdown::sampling;
use touchdown::scenario::{Dist, Scenario};

fn hold_down() -> Scenario {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    Scenario::from_file(&path).expect("scenarios/hold-down.toml reads")
}

#[test]
fn thrust_attitude_hold_in_the_fall_gives_no_net_impulse() {
    // In the fall only attitude hold fires: it asks for torque alone, which the allocation
    // gives from couples of the 1 N thrusters (no net force) and each thruster's on-time
    // carries its rounding to the next period, so the couple's two thrusters fire alike.
    // What force is left comes from the sampled thrust errors (3 % sd) and misalignments
    // (0.5 deg sd) of a couple's two thrusters, and from commands about both axes at once
    // whose thrusters round apart: samples 0-7 of the scenario, the net thrust impulse
    // along Z_B from the release to the first contact is at most 0.5 N s (the issue's
    // bound; before the least-propellant allocation 2.9-3.6 N s, the lander 8 % slower at
    // touchdown), and across Z_B too.
    let mut table = Table::new("thrust: net impulse of attitude hold in the fall");
    let s = hold_down();
    let model = Model::new(&s);
    for index in 0..8 {
        let sample = sampling::sample(&s, index);
        let (mut impulse, mut flow, mut touched) = (glam::DVec3::ZERO, 0.0, false);
        run(&model, &sample, |r: &StepReport| {
            touched |= r.legs.iter().any(|l| l.in_contact());
            if !touched {
                impulse += r.thrust.force_b_n * r.dt_s;
                flow += r.thrust.flow_n * r.dt_s;
            }
        });
        let case = format!("sample {index} (thrust fired {flow:.2} N s)");
        table.at_most(&case, "|net impulse along Z_B| (N s)", impulse.z.abs(), 0.5);
        table.at_most(
            &case,
            "|net impulse across Z_B| (N s)",
            impulse.truncate().length(),
            0.5,
        );
    }
    table.finish();
}

/// When the hold-down of each of `samples` samples of `s` starts after the first contact
/// (the true time of the step in which a footpad first touched to the start of the step in
/// which the loop is first in hold-down), s; `None` where it never does.
fn hold_down_delays(s: &Scenario, samples: u64) -> Vec<(u64, Option<f64>)> {
    let model = Model::new(s);
    (0..samples)
        .map(|index| {
            let sample = sampling::sample(s, index);
            let (mut contact, mut hold) = (None, None);
            run(&model, &sample, |r: &StepReport| {
                let start = r.t_s - r.dt_s;
                if contact.is_none() && r.legs.iter().any(|l| l.in_contact()) {
                    contact = Some(start);
                }
                if hold.is_none() && r.control.as_ref().is_some_and(|c| c.phase == "hold_down") {
                    hold = Some(start);
                }
            });
            (index, contact.zip(hold).map(|(c, h)| h - c))
        })
        .collect()
}

#[test]
fn thrust_touchdown_switches_latch_until_the_loop_reads_them() {
    // The lander of hold-down.toml at 1 and 2 Hz without latency, 20 N of hold-down: its
    // first contact is an impact of a few milliseconds (the contact spring), after which
    // it hops for seconds in milligravity, so a loop that looked only at the step before
    // an instant missed most first contacts (at 2 Hz, 1 of 12 hold-downs started within a
    // period, one never). The switch latches at the first touching step: the hold-down
    // starts at the first control instant after the first contact, within one period of
    // it (the instant's own step may end up to one flight step, 0.05 s, after it: the
    // bound is the period plus that).
    let mut table = Table::new("thrust: hold-down starts within a period of first contact");
    for rate in [1.0, 2.0] {
        let mut s = hold_down();
        let c = s.control.as_mut().expect("a control loop");
        c.rate_hz = rate;
        c.latency_periods = 0;
        c.hold_down.as_mut().expect("a hold-down").thrust_n = Dist::Fixed(20.0);
        let flight_step = s.simulation.flight_step_max_s;
        for (index, delay) in hold_down_delays(&s, 12) {
            let case = format!("{rate} Hz, sample {index}");
            table.at_most(
                &case,
                "delay (s; inf: never)",
                delay.unwrap_or(f64::INFINITY),
                1.0 / rate + flight_step,
            );
            table.at_most(&case, "-delay (s)", -delay.unwrap_or(0.0), 0.0);
        }
    }
    table.finish();
}
