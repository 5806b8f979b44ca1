//! Propellant: the thrust's integral over isp g0.

use crate::common::Table;
use touchdown::reference::{Model, StepReport, run};
use touchdown::sampling;
use touchdown::scenario::{G0_M_S2, Scenario};

#[test]
fn thrust_propellant_is_the_flow_integral() {
    // Whole reference runs of scenarios/hold-down.toml samples (attitude hold in the
    // stepped fall, hold-down after contact, sampled thruster errors and sensor noise),
    // at its Isp (220 s) and at 300 s: the propellant the loop books is the integral of
    // the firing thrusters' thrust magnitudes over the steps, over isp g0, to rounding
    // (relative 1e-9: the loop sums thrust times segment, the steps split each segment;
    // ~1e5 additions of rounding 1e-16). The hold-down impulse is a part of that
    // integral: at most it (plus rounding). The on-time is the thrusters firing, counted
    // per step, times the step (same tolerance).
    let mut table = Table::new("thrust: propellant = integral of thrust / (isp g0)");
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let base = Scenario::from_file(&path).expect("scenarios/hold-down.toml reads");
    for isp in [220.0, 300.0] {
        let mut s = base.clone();
        s.propulsion.isp_s = isp;
        let model = Model::new(&s);
        for index in 0..8 {
            let sample = sampling::sample(&s, index);
            let (mut impulse, mut on_time, mut steps) = (0.0, 0.0, 0u64);
            let summary = run(&model, &sample, |r: &StepReport| {
                impulse += r.thrust.flow_n * r.dt_s;
                let firing = r
                    .control
                    .as_ref()
                    .map_or(0, |c| c.thrust_n.iter().filter(|&&f| f > 0.0).count());
                on_time += firing as f64 * r.dt_s;
                steps += 1;
            });
            let c = *summary.control.expect("a control summary");
            let case = format!(
                "isp {isp} sample {index} ({:?} at {:.1} s, {steps} steps, hold-down {:.1} N)",
                summary.outcome, summary.decided_s, c.hold_down_thrust_n
            );
            table.relative(
                &case,
                "propellant (kg)",
                c.propellant_kg,
                impulse / (isp * G0_M_S2),
                1e-9,
            );
            table.relative(&case, "on-time (s)", c.on_time_s, on_time, 1e-9);
            table.at_most(
                &case,
                "hold-down impulse - impulse (N s)",
                c.hold_down_impulse_n_s - impulse,
                1e-9 * impulse,
            );
        }
    }
    table.finish();
}
