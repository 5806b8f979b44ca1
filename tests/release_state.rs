//! The touchdown state at the release of a descent (issue 30 point 1): the `release_*`
//! state columns are the release velocity seen in the surface plane's frame, and the free
//! fall that follows carries them to the touchdown state at the first contact by gravity
//! alone (closed form: the velocity grows by `g t` straight down).

use crate::common::{TempDir, arrow_column, touchdown};

#[test]
fn the_fall_from_the_release_carries_its_state_to_the_touchdown() {
    let dir = TempDir::new("release-state");
    // descent.toml with thrusters as built (no thrust or alignment errors): the attitude
    // hold of the fall then fires pure couples, and no force but gravity acts until the
    // first contact.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenarios/descent.toml"
    ))
    .unwrap()
    .replace("thrust_error_sd = 0.03", "thrust_error_sd = 0.0")
    .replace("misalignment_sd_deg = 0.5", "misalignment_sd_deg = 0.0");
    assert!(text.contains("thrust_error_sd = 0.0") && text.contains("misalignment_sd_deg = 0.0"));
    dir.write("d.toml", &text);
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "d.toml",
            "--samples",
            "24",
            "--out",
            "d.arrow",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let path = dir.join("d.arrow");
    let col = |name: &str| arrow_column(&path, name).unwrap_or_else(|| panic!("no {name}"));
    let (slope, azimuth) = (col("slope_deg"), col("downhill_azimuth_deg"));
    let (released, first) = (col("release_time_s"), col("first_contact_s"));
    let v: Vec<Vec<f64>> = ["vx", "vy", "vz"]
        .iter()
        .map(|a| col(&format!("release_{a}_m_s")))
        .collect();
    let (vn, vt, az) = (
        col("release_normal_speed_m_s"),
        col("release_tangential_speed_m_s"),
        col("release_tangential_azimuth_deg"),
    );
    let (tn, tt, taz) = (
        col("touchdown_normal_speed_m_s"),
        col("touchdown_tangential_speed_m_s"),
        col("touchdown_tangential_azimuth_deg"),
    );
    let g = 0.0168; // the default gravity, m/s^2
    let mut checked = 0;
    for i in 0..slope.len() {
        if released[i].is_nan() {
            continue;
        }
        let (a, b) = (slope[i].to_radians(), azimuth[i].to_radians());
        // The plane's frame (MODEL.md section 4): n, downhill u, v = n x u.
        let n = [a.sin() * b.cos(), a.sin() * b.sin(), a.cos()];
        let u = [a.cos() * b.cos(), a.cos() * b.sin(), -a.sin()];
        let w = [
            n[1] * u[2] - n[2] * u[1],
            n[2] * u[0] - n[0] * u[2],
            n[0] * u[1] - n[1] * u[0],
        ];
        let dot = |p: [f64; 3]| p[0] * v[0][i] + p[1] * v[1][i] + p[2] * v[2][i];
        // The release columns are the release velocity in that frame (to rounding).
        assert!((vn[i] + dot(n)).abs() < 1e-12, "sample {i}");
        let (along_u, along_v) = (dot(u), dot(w));
        assert!((vt[i] - along_u.hypot(along_v)).abs() < 1e-12, "sample {i}");
        assert!(
            (az[i] - along_v.atan2(along_u).to_degrees()).abs() < 1e-9,
            "sample {i}"
        );
        // The fall: t from the release to the start of the first contact's step (where the
        // touchdown state is taken); gravity adds g t cos(a) towards the plane and g t sin(a)
        // downhill. The step integrates a constant acceleration exactly; 1e-6 m/s allows
        // the rounding of some 10^5 steps.
        let t = first[i] - released[i];
        let (en, eu, ev) = (vn[i] + g * t * a.cos(), along_u + g * t * a.sin(), along_v);
        assert!(
            (tn[i] - en).abs() < 1e-6,
            "sample {i}: {} against {en}",
            tn[i]
        );
        assert!(
            (tt[i] - eu.hypot(ev)).abs() < 1e-6,
            "sample {i}: {} against {}",
            tt[i],
            eu.hypot(ev)
        );
        if eu.hypot(ev) > 1e-3 {
            let d = (taz[i] - ev.atan2(eu).to_degrees() + 180.0).rem_euclid(360.0) - 180.0;
            assert!(d.abs() < 1e-3, "sample {i}: azimuth off by {d} deg");
        }
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} of 24 samples released");
}
