//! Attitude hold: PD torque, continuous (the closed-form step response) and by pulse-width
//! thrusters (the pulse width gives the commanded torque).

use super::{Sim, constant_thrust, flight_scenario, posed};
use crate::common::Table;
use crate::lander::{quiet, sample_in};
use glam::DVec3;
use touchdown::control::{ControlModel, LaneControl, Truth, attitude_torque};
use touchdown::reference::Model;
use touchdown::scenario::Sample;
use touchdown::scenario::{Dist, Scenario, Sensors, Target};

/// The tilt of `I theta'' = -kp theta - kd theta'` from `theta0` at rest, and its
/// impulse response (the tilt after a unit angular-velocity kick), at `t`.
fn pd_response(kp: f64, kd: f64, inertia: f64, theta0: f64, t: f64) -> (f64, f64) {
    let omega = (kp / inertia).sqrt();
    let zeta = kd / (2.0 * (kp * inertia).sqrt());
    if zeta < 1.0 {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let decay = (-zeta * omega * t).exp();
        let (s, c) = (wd * t).sin_cos();
        (theta0 * decay * (c + zeta * omega / wd * s), decay * s / wd)
    } else {
        let root = omega * (zeta * zeta - 1.0).sqrt();
        let (s1, s2) = (-zeta * omega + root, -zeta * omega - root);
        let (e1, e2) = ((s1 * t).exp(), (s2 * t).exp());
        (
            theta0 * (s2 * e1 - s1 * e2) / (s2 - s1),
            (e1 - e2) / (s1 - s2),
        )
    }
}

#[test]
fn thrust_attitude_pd_follows_the_step_response() {
    // A body moment from `attitude_torque` (kp, kd, no deadband, target Z_I), recomputed
    // at the start of every 1 ms step and held over it, far above the surface: the roll
    // theta from theta0 at rest follows I_x theta'' = -kp theta - kd theta' (the law's
    // error is the rotation vector, exactly linear in theta; turning about X_B alone
    // there is no gyroscopic term). Under- and overdamped gains, two initial tilts, over
    // 30 s (or at least five time constants).
    //
    // Tolerance: holding the torque over a step is a forcing d(t) = M_n - M(t) of mean
    // -(dt/2) M'(t); the error e = theta - exact obeys the same equation driven by d / I, so
    // |e| <= (dt / 2) max|M'| / I * int |h|, h the impulse response (`pd_response`), to
    // first order in dt (the forcing's zero-mean sawtooth adds O(dt^2)). Twice that bound.
    // A moment applied with the wrong sign, twice, or one step late would be off by a
    // sizeable fraction of theta0.
    let mut table = Table::new("thrust: attitude PD (continuous torque), roll step response");
    let dt = 1e-3;
    for (kp, kd) in [
        (20.0, 5.0),
        (100.0, 20.0),
        (20.0, 40.0),
        (5.0, 60.0),
        (2.0, 1.0),
    ] {
        for theta0_deg in [5.0, 40.0] {
            let mut s = flight_scenario(0.0168, dt);
            s.simulation.t_max_s = 1e3;
            let mut sim = Sim::of(&s, posed([theta0_deg, 0.0, 0.0], [0.0; 3], [0.0; 3]));
            let inertia = sim.model.inertia_kg_m2.x;
            let theta0 = theta0_deg.to_radians();
            let zeta = kd / (2.0 * (kp * inertia).sqrt());
            let omega = (kp / inertia).sqrt();
            // The slowest decay rate of the response.
            let slowest = if zeta < 1.0 {
                zeta * omega
            } else {
                omega * (zeta - (zeta * zeta - 1.0).sqrt())
            };
            let duration = (5.0 / slowest).max(30.0);
            let steps = (duration / dt).round() as usize;
            sim.state.thrust = constant_thrust(DVec3::ZERO, DVec3::ZERO);
            let (mut worst, mut off_axis): (f64, f64) = (0.0, 0.0);
            // At t = 0: theta' = 0, theta'' = -kp theta0 / I.
            let mut max_dm = kd * kp * theta0 / inertia;
            let mut int_h = 0.0f64;
            for k in 0..steps {
                let b = sim.state.body;
                sim.state.thrust.moment_b_n_m =
                    attitude_torque(kp, kd, 0.0, b.attitude, b.rate_rad_s, DVec3::Z);
                sim.step_by(dt);
                let t = (k + 1) as f64 * dt;
                let q = sim.state.body.attitude;
                let theta = 2.0 * q.x.atan2(q.w);
                let (exact, h) = pd_response(kp, kd, inertia, theta0, t);
                worst = worst.max((theta - exact).abs());
                off_axis = off_axis.max(q.y.abs() + q.z.abs() + sim.state.body.rate_rad_s.y.abs());
                // Along the exact response: theta' = -(kp / I) theta0 h (it solves the
                // same equation from 0 with theta''(0) = -(kp / I) theta0),
                // theta'' = -(kp theta + kd theta') / I, M' = -kp theta' - kd theta''; and
                // the integral of |h|.
                let rate = -kp / inertia * theta0 * h;
                let accel = -(kp * exact + kd * rate) / inertia;
                max_dm = max_dm.max((kp * rate + kd * accel).abs());
                int_h += h.abs() * dt;
            }
            let tolerance = 2.0 * (0.5 * dt) * max_dm / inertia * int_h;
            let case = format!(
                "kp {kp} kd {kd} (zeta {zeta:.2}, w {omega:.2}) theta0 {theta0_deg} deg, {duration:.0} s"
            );
            table.at_most(&case, "max |theta - exact| (rad)", worst, tolerance);
            table.at_most(&case, "off-axis q_y, q_z, w_y", off_axis, 1e-12);
        }
    }
    table.finish();
}

/// The control model of scenarios/hold-down.toml with only attitude hold (gain `kp`, no
/// deadband), no sensor errors, no thruster errors and no latency.
fn attitude_hold_model(kp: f64) -> (Scenario, ControlModel) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/hold-down.toml");
    let mut s = Scenario::from_file(&path).expect("scenarios/hold-down.toml reads");
    s.propulsion.thrust_error_sd = 0.0;
    s.propulsion.misalignment_sd_deg = 0.0;
    let c = s.control.as_mut().expect("it has a control loop");
    c.latency_periods = 0;
    c.sensors = Sensors::default();
    c.hold_down = None;
    let a = c.attitude_hold.as_mut().expect("it has attitude hold");
    a.kp_n_m_per_rad = Dist::Fixed(kp);
    a.kd_n_m_s_per_rad = Dist::Fixed(40.0);
    a.deadband_deg = 0.0;
    a.target = Target::Vertical;
    let model = Model::new(&s).control.expect("a control model");
    (s, model)
}

#[test]
fn thrust_attitude_pulse_width_gives_the_commanded_torque() {
    // The thrusters of scenarios/hold-down.toml, attitude hold only (no noise, bias,
    // errors or latency, no deadband), a lander held at a fixed tilt at rest: over each
    // control period the thrust's moment, integrated over the segments between the loop's
    // events and divided by the period, must equal the law's command kp * (rotation
    // vector from Z_B to Z_I), clipped as a whole where the thrusters cannot give it
    // (the largest duty 1). Each thruster's on-time is quantised to whole minimum on-times
    // together with what it carries from its earlier periods (at most half one either
    // way), so one period's on-time is off by at most one minimum on-time and the sum over
    // K periods by at most half one: per axis, with `bound` the sum over the thrusters
    // fired of |their torque about it| * min_on / (2 period) (for the attitude couples,
    // two 1 N thrusters 0.45 m from the CG, 10 ms, 0.1 s: 0.045 N m), one period's mean
    // torque is within 2 bound, the mean over three periods within bound / 3. A torque
    // comes from couples whose two thrusters are asked alike and fire alike: the mean
    // force is zero (1e-9 N: rounding of sums of 1 N forces; the nearest one-sided firing
    // would be 1 N * 10 ms / 0.1 s = 0.1 N). Three periods each, every period alike (a
    // fixed truth). Tilts about X_B, Y_B and both, from below one impulse bit (0.05 deg at
    // kp 20) to saturated (10 deg), two gains.
    let mut table = Table::new("thrust: attitude hold by pulse-width thrusters, torque per period");
    for kp in [20.0, 5.0] {
        let (s, m) = attitude_hold_model(kp);
        let period = m.period_s;
        for (roll, pitch) in [
            (0.05, 0.0),
            (1.0, 0.0),
            (0.0, -2.0),
            (2.5, 0.0),
            (-1.0, 1.5),
            (0.0, 10.0),
            (-6.0, 8.0),
        ] {
            let attitude = touchdown::reference::run::from_euler_zyx(
                0.0,
                f64::to_radians(pitch),
                f64::to_radians(roll),
            );
            let command = attitude_torque(kp, 40.0, 0.0, attitude, DVec3::ZERO, DVec3::Z);
            // The law's torque, scaled down as a whole where a thruster would need more
            // than the period (`Allocation::duties`), from each axis's unit duties.
            let mut need = vec![0.0; m.thrusters.len()];
            for (axis, w) in command.to_array().into_iter().enumerate() {
                let k = (3 + axis) * 2 + usize::from(w < 0.0);
                if let Some(unit) = &m.allocation.unit[k] {
                    for (n, u) in need.iter_mut().zip(unit) {
                        *n += w.abs() * u;
                    }
                }
            }
            let most = need.iter().copied().fold(0.0, f64::max);
            let expected = command / most.max(1.0);
            // Per axis: the thrusters fired, their torque about it, half a minimum on-time.
            let mut bound = DVec3::ZERO;
            for (j, t) in m.thrusters.iter().enumerate() {
                if need[j] > 0.0 {
                    let f = DVec3::from_array(t.direction) * t.max_thrust_n;
                    let tau = DVec3::from_array(t.position_m).cross(f);
                    bound += tau.abs() * (t.min_on_time_s / (2.0 * period));
                }
            }
            let sample = Sample {
                seed: 7,
                ..sample_in(&s, quiet())
            };
            let mut control = LaneControl::new(&m, &sample);
            let mut t_s = 0.0;
            let truth = |t_s: f64| Truth {
                t_s,
                position_m: DVec3::new(0.0, 0.0, 100.0),
                velocity_m_s: DVec3::ZERO,
                attitude,
                rate_rad_s: DVec3::ZERO,
                contact: false,
                touching: false,
                normal: DVec3::Z,
            };
            let case = format!(
                "kp {kp} roll {roll} pitch {pitch}: command {:.4} {:.4}, saturation {most:.2}",
                command.x, command.y
            );
            let mut over_periods = DVec3::ZERO;
            for p in 0..3 {
                let (mut torque, mut force, mut elapsed, mut segments) =
                    (DVec3::ZERO, DVec3::ZERO, 0.0, 0);
                while elapsed < period - 1e-12 {
                    let thrust = control.event(&m, &truth(t_s));
                    assert!(thrust.event_in_s.is_finite() && thrust.event_in_s > 0.0);
                    torque += thrust.moment_b_n_m * thrust.event_in_s;
                    force += thrust.force_b_n * thrust.event_in_s;
                    elapsed += thrust.event_in_s;
                    t_s += thrust.event_in_s;
                    segments += 1;
                    assert!(segments < 100, "{case}: the period never ends");
                }
                over_periods += torque;
                let (torque, force) = (torque / period, force / period);
                let quantity = |what: &str| format!("period {p}: {what}");
                table.close(
                    &case,
                    &quantity("segments sum to the period (s)"),
                    elapsed,
                    period,
                    1e-12,
                );
                for (axis, name) in [(0, "X"), (1, "Y"), (2, "Z")] {
                    table.close(
                        &case,
                        &quantity(&format!("mean torque {name} (N m)")),
                        torque[axis],
                        expected[axis],
                        2.0 * bound[axis] + 1e-12,
                    );
                }
                table.at_most(&case, &quantity("|mean force| (N)"), force.length(), 1e-9);
            }
            let mean = over_periods / (3.0 * period);
            for (axis, name) in [(0, "X"), (1, "Y"), (2, "Z")] {
                table.close(
                    &case,
                    &format!("mean torque {name} over three periods (N m)"),
                    mean[axis],
                    expected[axis],
                    bound[axis] / 3.0 + 1e-12,
                );
            }
        }
    }
    table.finish();
}
