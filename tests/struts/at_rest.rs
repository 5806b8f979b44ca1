//! At rest on a level surface, each of n legs carries `m g / n`, split along and across
//! its strut by the strut's angle from the vertical.

use super::{Columns, level_drop};
use crate::common::{TempDir, touchdown};
use touchdown::scenario::Scenario;

/// The scenario of an `n`-legged lander whose rigid struts (no damper) lean outward by
/// `theta_deg` from the vertical, each in the vertical plane through its footpad.
fn leaning(legs: usize, theta_deg: f64) -> String {
    let lander = format!(
        "[lander]\nlegs = {legs}\nfootpad_radius_m = 0.7\ncg_height_m = 0.5\nfirst_leg_azimuth_deg = 30.0\n"
    );
    let tips = Scenario::from_toml(&lander).unwrap().lander.tips_m();
    let theta = theta_deg.to_radians();
    let axes: Vec<String> = tips
        .iter()
        .map(|t| {
            let phi = t[1].atan2(t[0]);
            format!(
                "[{:?}, {:?}, {:?}]",
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                -theta.cos()
            )
        })
        .collect();
    format!(
        "{lander}\n[damper]\nenabled = false\nstrut_axis = [{}]\n\n{}",
        axes.join(", "),
        level_drop(0.05)
    )
}

#[test]
fn at_rest_each_strut_carries_its_share_of_the_weight_along_and_across_it() {
    // A gentle level drop (0.04 m/s) of 3 and 4 legs whose struts lean outward by 20 and
    // 40 deg: at rest each footpad takes the weight's share m g / n straight up (the
    // surface is level, and a lander that fell straight down without turning never
    // stretched a friction spring: its footpads moved only along the normal), so the strut
    // carries m g / n cos(theta) along it and m g / n sin(theta) across it. Read from the
    // trace's last row (the state at the decision, `stable` after the 2 s hold). The
    // tolerance, 1e-6 of the share (4e-7 N of 0.42 N): the spring-damper of each leg
    // (k 5e4 N/m, c 1.1e3 N s/m on a quarter of 100 kg) damps its oscillation at
    // c / 2m = 22 per second, so after the hold it is far below 1e-9 of the force; what
    // remains is rounding and the friction left from the settling (0 by the symmetry of a
    // straight fall, to rounding). Measured: within 1e-12 N.
    let dir = TempDir::new("struts-at-rest");
    let weight = 100.0 * 0.0168;
    for legs in [3usize, 4] {
        for theta in [20.0f64, 40.0] {
            let name = format!("lean-{legs}-{theta}.toml");
            dir.write(&name, &leaning(legs, theta));
            let out = format!("lean-{legs}-{theta}.arrow");
            touchdown(dir.path(), &["trace", "--scenario", &name, "--out", &out]).assert_ok();
            let t = Columns::in_dir(&dir, &out);
            assert_eq!(t.meta("touchdown.outcome"), "stable", "{name}");
            let share = weight / legs as f64;
            let (along, across) = (
                share * theta.to_radians().cos(),
                share * theta.to_radians().sin(),
            );
            for k in 0..legs {
                let axial = *t.f64s(&format!("leg{k}_axial_force_n")).last().unwrap();
                let side = *t.f64s(&format!("leg{k}_side_force_n")).last().unwrap();
                println!(
                    "{legs} legs, {theta} deg, leg {k}: axial {axial:.12} N (closed form {along:.12}), side {side:.12} N ({across:.12})"
                );
                assert!(
                    (axial - along).abs() <= 1e-6 * share,
                    "{name} leg {k}: axial {axial} N, closed form {along} N"
                );
                assert!(
                    (side - across).abs() <= 1e-6 * share,
                    "{name} leg {k}: side {side} N, closed form {across} N"
                );
            }
        }
    }
}
