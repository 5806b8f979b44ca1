//! The touchdown state (MODEL.md section 9): the velocity, tilt and rates in which a lander
//! meets the surface, against the closed form of a fall.

use super::classify;
use crate::common::Table;
use crate::lander::on_slope;
use touchdown::scenario::{Inputs, Scenario};

/// The speed of the default lander's straight fall from release height `h` at the first
/// contact with a slope of `slope_deg` (its lowest footpad `clearance_m` = c above it along
/// the normal: it falls c / cos(a) more): sqrt(2 g (h + c / cos a)); and the bound on its
/// error, g times the longest flight step (see the first test).
fn fall_speed(s: &Scenario, h: f64, slope_deg: f64) -> (f64, f64) {
    let (g, c) = (s.gravity_m_s2, s.initial.clearance_m);
    let a = slope_deg.to_radians();
    (
        (2.0 * g * (h + c / a.cos())).sqrt(),
        g * s.simulation.flight_step_max_s,
    )
}

#[test]
fn a_straight_fall_meets_the_surface_at_its_closed_form_speed() {
    // The default lander upright (attitude errors against the local vertical, none here),
    // no velocity error and no rates, starting at touchdown: falling straight down at
    // s0 = sqrt(2 g h) from the release height h, its lowest footpad `clearance_m` = c
    // above the slope along the normal. It meets a slope of angle a after falling
    // c / cos(a) more, plus the footpad's depth at the start of the first step that sees
    // it touching (the state recorded: at most the travel of the step before, s dt), so
    // its speed is s = sqrt(2 g (h + c / cos a)) within g dt (dt at most the longest
    // flight step, 0.05 s: 8.4e-4 m/s; measured 1e-5). Its velocity is vertical, so towards the
    // surface s cos(a) and along it s sin(a), pointing downhill (azimuth 0, to rounding;
    // and 0 from X_B, which points downhill at yaw 0), and Z_B is tilted from the normal by
    // the slope itself; no rates. On level ground the speed along the surface is exactly 0
    // and its azimuths are undefined (NaN: null in the sweep).
    let mut table = Table::new("touchdown state of a straight fall");
    let s = Scenario::default();
    for slope in [0.0, 10.0, 25.0] {
        for h in [1.0, 5.0, 10.0] {
            let inputs = Inputs {
                release_height_m: h,
                ..on_slope(slope, 0.0)
            };
            let summary = classify(&s, inputs);
            let t = summary.touchdown.expect("it touches");
            let a = f64::to_radians(slope);
            let (speed, bound) = fall_speed(&s, h, slope);
            let case = format!("slope {slope} deg, h {h} m");
            table.close(
                &case,
                "normal speed (m/s)",
                t.normal_speed_m_s,
                speed * a.cos(),
                bound,
            );
            table.close(
                &case,
                "tangential speed (m/s)",
                t.tangential_speed_m_s,
                speed * a.sin(),
                bound,
            );
            table.close(&case, "tilt (deg)", t.tilt_deg, slope, 1e-9);
            let rates = t.rate_deg_s.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            table.at_most(&case, "|rates| (deg/s)", rates, 0.0);
            if slope > 0.0 {
                table.close(&case, "azimuth (deg)", t.tangential_azimuth_deg, 0.0, 1e-9);
                table.close(
                    &case,
                    "azimuth from X_B (deg)",
                    t.tangential_azimuth_body_deg,
                    0.0,
                    1e-9,
                );
            } else {
                table.equal(
                    &case,
                    "tangential speed exactly 0",
                    t.tangential_speed_m_s,
                    0.0,
                );
                table.equal(
                    &case,
                    "azimuths undefined",
                    t.tangential_azimuth_deg.is_nan() && t.tangential_azimuth_body_deg.is_nan(),
                    true,
                );
            }
        }
    }
    table.finish();
}

#[test]
fn a_sideways_fall_meets_the_surface_across_the_slope() {
    // On a 20 deg slope facing downhill along +X_I, a velocity error of 0.1 m/s along +Y_I
    // (across the slope: horizontal and along `tangent_v = n x downhill`) adds to the
    // vertical fall. Along the surface the velocity is then (s sin a) downhill and 0.1 m/s
    // across: its azimuth from downhill is atan2(0.1, s sin a), towards the normal still
    // s cos a (the error is in the plane). With the lander yawed by 90 deg, X_B points
    // across the slope (+Y_I), so the azimuth from X_B is the same less 90 deg. Speeds
    // within g dt as above (the azimuth by as much over the speeds: 1 deg is far wider
    // than that, 0.5 deg is the bound used).
    let mut table = Table::new("touchdown state of a sideways fall");
    let s = Scenario::default();
    let (slope, h, across) = (20.0, 5.0, 0.1);
    let (speed, bound) = fall_speed(&s, h, slope);
    for yaw in [0.0, 90.0] {
        let inputs = Inputs {
            release_height_m: h,
            velocity_error_y_m_s: across,
            yaw_deg: yaw,
            ..on_slope(slope, 0.0)
        };
        let t = classify(&s, inputs).touchdown.expect("it touches");
        let a = f64::to_radians(slope);
        let azimuth = across.atan2(speed * a.sin()).to_degrees();
        let case = format!("yaw {yaw} deg");
        table.close(
            &case,
            "normal speed (m/s)",
            t.normal_speed_m_s,
            speed * a.cos(),
            bound,
        );
        table.close(
            &case,
            "tangential speed (m/s)",
            t.tangential_speed_m_s,
            (speed * a.sin()).hypot(across),
            bound,
        );
        table.close(
            &case,
            "azimuth (deg)",
            t.tangential_azimuth_deg,
            azimuth,
            0.5,
        );
        table.close(
            &case,
            "azimuth from X_B (deg)",
            t.tangential_azimuth_body_deg,
            azimuth - yaw,
            0.5,
        );
    }
    table.finish();
}
