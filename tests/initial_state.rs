//! A scenario that starts at the touchdown state (`[initial]` `normal_speed_m_s`,
//! `tangential_speed_m_s`, `tangential_azimuth_deg`, issue 30 point 6): the sweep's
//! `touchdown_*` columns give back the state it was given, its drawn values are columns, a
//! table of inputs may give them, and what cannot go with them is refused.

use crate::common::{TempDir, arrow_column, bad_scenario, check_bad_input, touchdown};

/// The fall and the velocity errors fixed at 0, as the touchdown state requires.
const NO_FALL: &str = "release_height_m = 0.0
velocity_error_x_m_s = 0.0
velocity_error_y_m_s = 0.0
velocity_error_z_m_s = 0.0
";

/// Four slopes (a grid: sample `i` on slope `i mod 4`), downhill azimuths all round, the
/// attitude errors against the surface normal, and the whole touchdown state drawn.
fn scenario() -> String {
    format!(
        "samples = 64
[inputs]
slope_deg = {{ dist = \"grid\", min = 0.0, max = 30.0, count = 4 }}
{NO_FALL}[initial]
attitude_reference = \"surface\"
normal_speed_m_s = {{ dist = \"uniform\", min = 0.1, max = 0.4 }}
tangential_speed_m_s = {{ dist = \"uniform\", min = 0.2, max = 1.0 }}
tangential_azimuth_deg = {{ dist = \"uniform\", min = -180.0, max = 180.0 }}
"
    )
}

/// Panics, showing the run, unless it exited 0 (a sweep tells its kernel on stderr).
fn ok(run: crate::common::Run) {
    assert_eq!(run.code, Some(0), "{run}");
}

/// Gravity, `initial.clearance_m` and `simulation.flight_step_max_s` of the default
/// scenario.
const G_M_S2: f64 = 0.0168;
const CLEARANCE_M: f64 = 0.001;
const FLIGHT_STEP_MAX_S: f64 = 0.05;

/// The most gravity changes the velocity between the start at `vn` m/s towards the surface
/// and the state recorded at the first contact: g (c / vn + dt), over the clearance and at
/// most one step.
fn fall_change(vn: f64) -> f64 {
    G_M_S2 * (CLEARANCE_M / vn + FLIGHT_STEP_MAX_S)
}

#[test]
fn the_touchdown_columns_give_back_the_state_given() {
    let dir = TempDir::new("initial-state");
    dir.write("s.toml", &scenario());
    ok(touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--out",
            "s.arrow",
            "--quiet",
        ],
    ));
    let path = dir.join("s.arrow");
    let col = |name: &str| arrow_column(&path, name).unwrap_or_else(|| panic!("no {name}"));
    let (vn, vt, a) = (
        col("initial_normal_speed_m_s"),
        col("initial_tangential_speed_m_s"),
        col("initial_tangential_azimuth_deg"),
    );
    let (slope, roll, pitch) = (col("slope_deg"), col("roll_deg"), col("pitch_deg"));
    let rates = [
        col("rate_x_deg_s"),
        col("rate_y_deg_s"),
        col("rate_z_deg_s"),
    ];
    let (met_n, met_t, met_a, tilt) = (
        col("touchdown_normal_speed_m_s"),
        col("touchdown_tangential_speed_m_s"),
        col("touchdown_tangential_azimuth_deg"),
        col("touchdown_tilt_deg"),
    );
    assert_eq!(vn.len(), 64);
    assert!(slope.contains(&30.0) && slope.contains(&0.0));
    for i in 0..vn.len() {
        // The lowest footpad starts `clearance_m` above the terrain, and the columns hold
        // the state at the start of the first step that sees a footpad touching (so after
        // the clearance, plus at most the step before: MODEL.md section 9). In between,
        // gravity (g along any direction) acts for at most c / vn + dt, dt at most
        // `simulation.flight_step_max_s`, so it changes the velocity by at most
        // `fall_change` (at most 1.0e-3 m/s here; measured below 1e-4), and the speed towards
        // the surface only grows.
        let fall = fall_change(vn[i]);
        let at = format!(
            "sample {i}: slope {} given ({}, {}, {}), met ({}, {}, {})",
            slope[i], vn[i], vt[i], a[i], met_n[i], met_t[i], met_a[i]
        );
        assert!(
            met_n[i] >= vn[i] - 1e-12 && met_n[i] <= vn[i] + fall + 1e-12,
            "normal speed: {at}"
        );
        assert!(
            (met_t[i] - vt[i]).abs() <= fall + 1e-12,
            "speed along: {at}"
        );
        // The direction turns by at most asin(fall / vt) (vt >= 0.2 m/s: 0.25 deg).
        let turn = (fall / vt[i]).asin().to_degrees();
        let diff = (met_a[i] - a[i] + 540.0).rem_euclid(360.0) - 180.0;
        assert!(diff.abs() <= turn + 1e-9, "azimuth: {at}");
        // Against the surface normal, the attitude errors tilt Z_B by acos(cos roll cos
        // pitch); the rates (|w| deg/s, unchanged in a torque-free fall but for the
        // inertia's coupling, a second-order change over milliseconds: the factor 1.5)
        // turn it by at most |w| (c / vn + dt) before the contact.
        let expected = (roll[i].to_radians().cos() * pitch[i].to_radians().cos())
            .acos()
            .to_degrees();
        let w = rates.iter().map(|r| r[i] * r[i]).sum::<f64>().sqrt();
        assert!(
            (tilt[i] - expected).abs() <= 1.5 * w * fall / G_M_S2 + 1e-9,
            "tilt {} against {expected}: {at}",
            tilt[i]
        );
    }
}

#[test]
fn drawn_state_values_are_columns_and_a_table_may_give_them() {
    let dir = TempDir::new("initial-state-table");
    // The azimuth fixed: no column; the two speeds drawn: two columns.
    let text = scenario().replace(
        "tangential_azimuth_deg = { dist = \"uniform\", min = -180.0, max = 180.0 }",
        "tangential_azimuth_deg = 30.0",
    );
    dir.write("s.toml", &text);
    ok(touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--samples",
            "24",
            "--quiet",
        ],
    ));
    let path = dir.join("sweep.arrow");
    let vn = arrow_column(&path, "initial_normal_speed_m_s").expect("a drawn column");
    let vt = arrow_column(&path, "initial_tangential_speed_m_s").expect("a drawn column");
    assert!(arrow_column(&path, "initial_tangential_azimuth_deg").is_none());
    // A table of the sweep's own state values runs as the sweep did; it gives the fixed
    // azimuth too (its column then appears, as a parameter's the table gives does).
    let mut csv = String::from(
        "initial_normal_speed_m_s,initial_tangential_speed_m_s,initial_tangential_azimuth_deg\n",
    );
    for i in 0..vn.len() {
        csv += &format!("{:?},{:?},30.0\n", vn[i], vt[i]);
    }
    dir.write("t.csv", &csv);
    ok(touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--inputs",
            "t.csv",
            "--out",
            "t.arrow",
        ],
    ));
    let table = dir.join("t.arrow");
    for name in [
        "initial_normal_speed_m_s",
        "initial_tangential_speed_m_s",
        "touchdown_normal_speed_m_s",
        "touchdown_tangential_azimuth_deg",
        "touchdown_tilt_deg",
        "slope_deg",
    ] {
        let (a, b) = (arrow_column(&path, name), arrow_column(&table, name));
        let bits =
            |v: Option<Vec<f64>>| v.map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        assert_eq!(bits(a), bits(b), "{name}");
    }
    assert_eq!(
        arrow_column(&table, "initial_tangential_azimuth_deg"),
        Some(vec![30.0; vn.len()])
    );
    // A table of other state values: the landers meet the surface at those.
    let csv: String = std::iter::once("initial_normal_speed_m_s\n".to_string())
        .chain((0..8).map(|i| format!("{}\n", 0.1 + 0.05 * f64::from(i))))
        .collect();
    dir.write("n.csv", &csv);
    ok(touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            "s.toml",
            "--inputs",
            "n.csv",
            "--out",
            "n.arrow",
        ],
    ));
    let met = arrow_column(&dir.join("n.arrow"), "touchdown_normal_speed_m_s").unwrap();
    for (i, m) in met.iter().enumerate() {
        let vn = 0.1 + 0.05 * i as f64;
        // As above: at most `fall_change` faster.
        assert!(
            *m >= vn - 1e-12 && *m <= vn + fall_change(vn) + 1e-12,
            "{i}: {m}"
        );
    }
}

#[test]
fn what_cannot_go_with_a_touchdown_state_is_refused() {
    let cases = [
        bad_scenario(
            "a state with the default fall",
            "[initial]\nnormal_speed_m_s = 0.3\n",
            &["inputs.release_height_m", "fix", "at 0"],
        ),
        bad_scenario(
            "a state with a drawn velocity error",
            "[inputs]\nrelease_height_m = 0.0\nvelocity_error_x_m_s = 0.0\n\
             velocity_error_y_m_s = 0.0\n\
             velocity_error_z_m_s = { dist = \"uniform\", min = 0.0, max = 0.1 }\n\
             [initial]\nnormal_speed_m_s = 0.3\n",
            &["inputs.velocity_error_z_m_s", "at 0"],
        ),
        bad_scenario(
            "a state with a start at the release",
            "[initial]\nstart = \"release\"\ntangential_speed_m_s = 0.3\n",
            &[
                "initial.tangential_speed_m_s",
                "initial.start = \"touchdown\"",
            ],
        ),
        bad_scenario(
            "a speed along the surface alone",
            "[initial]\ntangential_azimuth_deg = 10.0\n",
            &["initial.tangential_azimuth_deg", "initial.normal_speed_m_s"],
        ),
        bad_scenario(
            "a normal speed away from the surface",
            "[initial]\nnormal_speed_m_s = { dist = \"uniform\", min = -0.1, max = 0.3 }\n",
            &["initial.normal_speed_m_s", "at least 0"],
        ),
        bad_scenario(
            "a negative speed along the surface",
            "[initial]\nnormal_speed_m_s = 0.2\ntangential_speed_m_s = -0.1\n",
            &["initial.tangential_speed_m_s", "at least 0"],
        ),
    ];
    let problems: Vec<String> = cases
        .iter()
        .flat_map(|c| check_bad_input("sweep", c, &[]))
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));

    // Tables: a state column without a state in the scenario, a fall with one.
    let dir = TempDir::new("initial-state-bad-table");
    dir.write("plain.toml", "samples = 4\n");
    dir.write("s.toml", &scenario());
    dir.write("state.csv", "initial_tangential_speed_m_s\n0.5\n");
    dir.write("fall.csv", "release_height_m\n1.0\n");
    for (scenario, table, expect) in [
        ("plain.toml", "state.csv", "initial.tangential_speed_m_s"),
        ("s.toml", "fall.csv", "inputs.release_height_m"),
    ] {
        let run = touchdown(
            dir.path(),
            &[
                "sweep",
                "--scenario",
                scenario,
                "--inputs",
                table,
                "--out",
                "x.arrow",
            ],
        );
        assert_eq!(run.code, Some(2), "{run}");
        assert!(run.stderr.contains(expect), "{run}");
        assert!(!dir.join("x.arrow").exists());
    }
}
