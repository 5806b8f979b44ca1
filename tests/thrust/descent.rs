//! Descent: the final burn releases the lander into a ballistic fall, and the descent's
//! parameters are drawn per sample.

use crate::common::Table;
use crate::lander::{CG_HEIGHT_M, quiet, sample_in};
use kernels::isa::Isa;
use touchdown::reference::{Model, StepReport, initial_state, run};
use touchdown::sampling;
use touchdown::scenario::{Dist, Inputs, Scenario};
use touchdown::slope::Surface;

/// The descent scenario of a perfect loop: four 1 N thrusters pushing along +Z_B and four
/// 10 N along -Z_B, symmetric about the CG, no thrust or pointing errors, no sensor
/// errors, no attitude hold; latency `latency` periods at 10 Hz; the descent of
/// scenarios/descent.toml (15 m at 0.2 m/s, braking 0.01 m/s^2, gain 2/s, release below
/// 0.01 m/s).
fn perfect_descent(latency: u32) -> Scenario {
    let mut text = String::from(
        "[initial]\nstart = \"descent\"\n[simulation]\nt_max_s = 150.0\n\
         [propulsion]\nthrust_error_sd = 0.0\nmisalignment_sd_deg = 0.0\n",
    );
    for (x, y) in [(0.45, 0.0), (-0.45, 0.0), (0.0, 0.45), (0.0, -0.45)] {
        for (z, thrust) in [(1.0, 1.0), (-1.0, 10.0)] {
            text += &format!(
                "[[thrusters]]\nposition_m = [{x}, {y}, 0.3]\ndirection = [0.0, 0.0, {z}]\n\
                 max_thrust_n = {thrust}\nmin_on_time_s = 0.01\n"
            );
        }
    }
    text += &format!(
        "[control]\nrate_hz = 10.0\nlatency_periods = {latency}\n[control.descent]\n\
         start_altitude_m = 15.0\nstart_speed_m_s = 0.2\nbraking_m_s2 = 0.01\n\
         gain_per_s = 2.0\nrelease_speed_m_s = 0.01\n"
    );
    Scenario::from_toml(&text).expect("the perfect descent reads")
}

#[test]
fn thrust_descent_releases_into_a_ballistic_fall() {
    // A perfect loop (sensors without errors) on level ground, upright and without rates,
    // at release heights 5, 7.5 and 10 m and latencies of 0, 1 and 2 periods:
    // - it releases at or below the release height (the altimeter reads the truth), at the
    //   first control instant whose reading allows it: no earlier reading of the descent
    //   was both at or below the release height and slower than the release speed;
    // - its approach rate at release is below the release speed (the sensed one is the
    //   true one);
    // - no thruster fires after the release (the burn's queued commands are dropped), and
    //   the first contact comes when the ballistic fall from the recorded release state,
    //   H + v t - g0 t^2 / 2 = 0, reaches the surface: t = (v + sqrt(v^2 + 2 g0 H)) / g0,
    //   within one 1 ms contact step (the upright gear's four footpads touch at once;
    //   tolerance 2 ms).
    let mut table = Table::new("thrust: descent, release and ballistic fall");
    let g0 = 0.0168;
    for latency in [0, 1, 2] {
        let s = perfect_descent(latency);
        let model = Model::new(&s);
        for release in [5.0, 7.5, 10.0] {
            let sample = sample_in(
                &s,
                Inputs {
                    release_height_m: release,
                    ..quiet()
                },
            );
            let mut fired_after_release = 0.0_f64;
            // Readings of the descent that would have allowed a release.
            let mut could_release = 0;
            let mut last_reading = f64::NAN;
            let summary = run(&model, &sample, |r: &StepReport| {
                let Some(c) = r.control.as_ref() else { return };
                if c.phase != "descent" {
                    fired_after_release = fired_after_release.max(r.thrust.flow_n);
                    return;
                }
                if let Some(s) = c.sensed
                    && s.t_s != last_reading
                {
                    last_reading = s.t_s;
                    let height = s.altitude_m - CG_HEIGHT_M;
                    could_release +=
                        usize::from(height <= release && s.velocity_m_s.z.abs() < 0.01);
                }
            });
            let c = *summary.control.expect("a control summary");
            let case = format!("latency {latency}, release height {release} m");
            table.equal(&case, "released", c.release_time_s.is_finite(), true);
            table.at_most(
                &case,
                "release altitude - release height (m)",
                c.release_altitude_m - release,
                0.0,
            );
            table.equal(
                &case,
                "readings that could release before the release",
                could_release,
                0,
            );
            let [vx, vy, vz] = c.release_velocity_m_s;
            table.at_most(&case, "|approach rate| at release (m/s)", vz.abs(), 0.01);
            table.at_most(
                &case,
                "horizontal speed at release (m/s)",
                vx.hypot(vy),
                1e-9,
            );
            table.at_most(&case, "thrust after release (N)", fired_after_release, 0.0);
            let fall = (vz + (vz * vz + 2.0 * g0 * c.release_altitude_m).sqrt()) / g0;
            table.close(
                &case,
                "first contact (s)",
                summary.first_contact_s.unwrap_or(f64::NAN),
                c.release_time_s + fall,
                2e-3,
            );
        }
    }
    table.finish();
}

/// `perfect_descent(latency)` with four 1 N thrusters pushing along +-X_B and +-Y_B
/// through the CG (0.45 m out at the CG's height) and, if `null`, the law nulling the
/// velocity along the surface (`null_lateral_velocity`).
fn lateral_descent(latency: u32, null: bool) -> Scenario {
    let mut s = perfect_descent(latency);
    for (x, y) in [(0.45, 0.0), (-0.45, 0.0), (0.0, 0.45), (0.0, -0.45)] {
        let mut t = s.thrusters[0].clone();
        t.position_m = [x, y, 0.0];
        t.direction = [-x / 0.45, -y / 0.45, 0.0];
        t.max_thrust_n = 1.0;
        s.thrusters.push(t);
    }
    let c = s.control.as_mut().and_then(|c| c.descent.as_mut()).unwrap();
    c.null_lateral_velocity = null;
    s
}

#[test]
fn thrust_descent_nulls_the_lateral_velocity_with_lateral_thrusters() {
    // The perfect loop on level ground with a navigation error of (0.10, -0.06) m/s along
    // the surface, latencies 0 and 2. The four lateral thrusters give at most 1 N / 100 kg
    // = 0.01 m/s^2 each way: the law (gain 2/s) asks for more until the speed is below
    // 0.005 m/s, so it brakes at about 0.01 m/s^2 for some 10-12 s and then decays as
    // exp(-2 t), well inside the descent (over 16 s from 15 m). One minimum on-time of a
    // lateral thruster changes the velocity by 1 N x 10 ms / 100 kg = 1e-4 m/s, and each
    // carries its rounding to the next period (at most half of that left), so at release
    // the speed along the surface is at most a few such quanta: 1e-3 m/s (the 0.117 m/s
    // of the error would be left without the law). Without `null_lateral_velocity` the
    // law asks for no force along the surface: the error is left to rounding (1e-9 m/s),
    // and the approach rate is below the release speed either way.
    let mut table = Table::new("thrust: descent nulls the velocity along the surface");
    let (ex, ey) = (0.10, -0.06);
    for latency in [0, 2] {
        for null in [true, false] {
            let s = lateral_descent(latency, null);
            let model = Model::new(&s);
            let sample = sample_in(
                &s,
                Inputs {
                    release_height_m: 7.5,
                    velocity_error_x_m_s: ex,
                    velocity_error_y_m_s: ey,
                    ..quiet()
                },
            );
            let summary = run(&model, &sample, |_: &StepReport| {});
            let c = *summary.control.expect("a control summary");
            let case = format!("latency {latency}, null_lateral_velocity {null}");
            table.equal(&case, "released", c.release_time_s.is_finite(), true);
            let [vx, vy, vz] = c.release_velocity_m_s;
            table.at_most(&case, "|approach rate| at release (m/s)", vz.abs(), 0.01);
            if null {
                table.at_most(&case, "speed along the surface (m/s)", vx.hypot(vy), 1e-3);
            } else {
                table.close(&case, "vx at release (m/s)", vx, ex, 1e-9);
                table.close(&case, "vy at release (m/s)", vy, ey, 1e-9);
            }
        }
    }
    table.finish();
}

#[test]
fn thrust_descent_parameters_are_drawn_per_sample() {
    // The descent's parameters are inputs like any other: a start altitude uniform in
    // 12-18 m and a braking on a grid of 0.005 and 0.01 m/s^2. Each sample starts with its
    // lowest footpad at its drawn altitude above the initial clearance (to rounding),
    // the grid alternates sample by sample (law parameters vary fastest), and the sweep's
    // rows carry the draws the initial state and the loop used.
    let mut s = perfect_descent(1);
    let d = s.control.as_mut().and_then(|c| c.descent.as_mut()).unwrap();
    d.start_altitude_m = Dist::Uniform {
        min: 12.0,
        max: 18.0,
    };
    d.braking_m_s2 = Dist::Grid {
        min: 0.005,
        max: 0.01,
        count: 2,
    };
    let model = Model::new(&s);
    let mut table = Table::new("thrust: descent parameters drawn per sample");
    let n = 16;
    let mut rows = Vec::new();
    let never = std::sync::atomic::AtomicUsize::new(0);
    touchdown::sweep::run_until(&s, &model, Isa::detect(), 0..n, 8, &never, |r| {
        rows.extend(r);
        Ok(())
    })
    .unwrap();
    let mut altitudes = Vec::new();
    for row in &rows {
        let sample = sampling::sample(&s, row.sample.index);
        let draw = model
            .control
            .as_ref()
            .and_then(|m| m.descent_draw(&sample))
            .expect("a descent");
        let case = format!("sample {}", row.sample.index);
        // The start puts the lowest footpad (along the slope's normal n) the clearance
        // above the surface, then raises the lander by the start altitude along Z_I: its
        // height above the plane is clearance + altitude n_z.
        let surface = Surface::of(&sample);
        let start = initial_state(&model, &surface, &sample);
        let n = surface.normal;
        let footpad = (model
            .legs
            .iter()
            .map(|l| n.dot(start.body.position_m + start.body.attitude * l.tip_m))
            .fold(f64::INFINITY, f64::min)
            - s.initial.clearance_m)
            / n.z;
        table.close(
            &case,
            "start footpad height (m)",
            footpad,
            draw.start_altitude_m,
            1e-12,
        );
        table.equal(
            &case,
            "braking on the grid (m/s^2)",
            draw.braking_m_s2,
            [0.005, 0.01][(row.sample.index % 2) as usize],
        );
        let row_draw = row
            .summary
            .control
            .as_ref()
            .and_then(|c| c.descent)
            .expect("the row's descent");
        table.equal(&case, "the row's draw", row_draw, draw);
        altitudes.push(draw.start_altitude_m);
    }
    let (lo, hi) = altitudes
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &a| {
            (lo.min(a), hi.max(a))
        });
    table.equal(
        "16 samples",
        "start altitudes within 12-18 m and not all one",
        lo >= 12.0 && hi <= 18.0 && hi - lo > 1.0,
        true,
    );
    table.finish();
}
