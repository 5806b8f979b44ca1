//! Accelerations under thrust (MODEL.md sections 7 and 9): a trace's `ax/ay/az_m_s2` are
//! `dv/dt` with every force, thrust included, and what an accelerometer reads (the trace's
//! `accel_z_body_m_s2`, the sweep's peak columns) is the specific force, contact plus
//! thrust; the kernels' peaks (a sweep) agree with the reference's (a trace).

use crate::common::{TempDir, touchdown};
use std::path::Path;
use touchdown::output::columns::Table;
use touchdown::scenario::Scenario;

/// The shipped scenario file `scenarios/NAME.toml`, as text.
fn shipped(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(format!("{name}.toml"));
    std::fs::read_to_string(path).unwrap()
}

/// Every column of the file at `path`.
fn read(path: &Path) -> Table {
    Table::read(path, |_| true).unwrap()
}

/// Row `i` of the columns named `x`, `y`, `z` of `t`, as a vector.
fn vector(t: &Table, [x, y, z]: [&str; 3], i: usize) -> [f64; 3] {
    [t.columns[x][i], t.columns[y][i], t.columns[z][i]]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

const VELOCITY: [&str; 3] = ["vx_m_s", "vy_m_s", "vz_m_s"];
const ACCELERATION: [&str; 3] = ["ax_m_s2", "ay_m_s2", "az_m_s2"];
const THRUST: [&str; 3] = ["thrust_b_x_n", "thrust_b_y_n", "thrust_b_z_n"];

#[test]
fn trace_acceleration_is_dv_dt_with_thrust() {
    // Samples 0-2 of hold-down.toml: attitude hold through a stepped fall, then 20 N of
    // hold-down for 10 s. Every step's row holds the velocity at its start and the
    // acceleration during it, so (v[i+1] - v[i]) / dt[i] is a[i] but for rounding: the
    // integrator adds the contact kick, gravity and the thrust to v in three roundings of
    // at most eps |v| each, the difference of two rounded velocities adds two more, and
    // the row's a is a sum and a quotient of a few roundings of |a|: 8 eps (|v[i]| +
    // |v[i+1]|) / dt + 8 eps |a| bounds it with margin (measured: 1e-13 m/s^2 at 1 ms
    // steps). Rows of steps shortened to nearly nothing at a switch (dt 1e-17 s) get a
    // bound as wide as rounding makes it. Before thrust was counted the rows under thrust
    // were off by |thrust| / m (0.18 m/s^2 in the fall, up to 0.4 in hold-down).
    //
    // The accelerometer column is the specific force along Z_B: (a - g) . Z_B, within a
    // few roundings of |a| (1e-12 relative, or of 1e-12 m/s^2 absolute); and where no
    // leg touches, the thrust alone: thrust_b_z / m.
    let dir = TempDir::new("trace_acceleration_is_dv_dt_with_thrust");
    // The hold-down fixed at 20 N, so that the net thrust is large in every sample (the
    // attitude hold's couples give none, and a drawn thrust of 0.1 N fires once in 3 s).
    let text = shipped("hold-down").replace(
        "thrust_n = { dist = \"uniform\", min = 0.0, max = 40.0 }",
        "thrust_n = 20.0",
    );
    assert!(
        text.contains("thrust_n = 20.0"),
        "the hold-down's thrust is set"
    );
    let scenario = Scenario::from_toml(&text).unwrap();
    let (mass, g0) = (scenario.lander.mass_kg, scenario.gravity_m_s2);
    let file = dir.write("hold-down.toml", &text);
    let file = file.to_str().unwrap();
    let eps = f64::EPSILON;
    for sample in ["0", "1", "2"] {
        let out = format!("trace{sample}.arrow");
        touchdown(
            dir.path(),
            &[
                "trace",
                "--scenario",
                file,
                "--sample",
                sample,
                "--out",
                &out,
            ],
        )
        .assert_ok();
        let t = read(&dir.join(&out));
        let (mut worst, mut thrust_rows, mut flight_rows) = (0.0f64, 0, 0);
        for i in 0..t.rows - 1 {
            let dt = t.columns["dt_s"][i];
            let (v0, v1) = (vector(&t, VELOCITY, i), vector(&t, VELOCITY, i + 1));
            let a = vector(&t, ACCELERATION, i);
            let thrust = vector(&t, THRUST, i);
            if dt > 0.0 {
                let bound = 8.0 * eps * (norm(v0) + norm(v1)) / dt + 8.0 * eps * norm(a);
                for k in 0..3 {
                    let off = ((v1[k] - v0[k]) / dt - a[k]).abs();
                    assert!(
                        off <= bound,
                        "sample {sample}, row {i} (t {} s, dt {dt} s), axis {k}: dv/dt - a = \
                         {off:e} m/s^2, beyond {bound:e} (thrust {thrust:?} N)",
                        t.columns["t_s"][i]
                    );
                    if dt >= 1e-6 {
                        worst = worst.max(off);
                    }
                }
                thrust_rows += usize::from(norm(thrust) > 1.0 && dt >= 1e-4);
            }
            // The specific force along Z_B, from the row's attitude.
            let (w, x, y, z) = (
                t.columns["qw"][i],
                t.columns["qx"][i],
                t.columns["qy"][i],
                t.columns["qz"][i],
            );
            let z_body = [
                2.0 * (x * z + w * y),
                2.0 * (y * z - w * x),
                1.0 - 2.0 * (x * x + y * y),
            ];
            let specific = [a[0], a[1], a[2] + g0];
            let along: f64 = (0..3).map(|k| specific[k] * z_body[k]).sum();
            let reading = t.columns["accel_z_body_m_s2"][i];
            let tolerance = 1e-12 * norm(a).max(1.0);
            assert!(
                (reading - along).abs() <= tolerance,
                "sample {sample}, row {i}: accelerometer {reading} against (a - g) . Z_B {along}"
            );
            let touching = (0..4).any(|l| t.columns[&format!("leg{l}_normal_force_n")][i] > 0.0);
            if !touching && dt > 0.0 {
                flight_rows += 1;
                let alone = thrust[2] / mass;
                assert!(
                    (reading - alone).abs() <= 1e-12 * alone.abs().max(1.0),
                    "sample {sample}, row {i}: accelerometer {reading} in flight, thrust_b_z / m \
                     {alone}"
                );
            }
        }
        println!(
            "sample {sample}: {} rows, {thrust_rows} under thrust, {flight_rows} in flight; \
             worst |dv/dt - a| {worst:.1e} m/s^2 (steps of 1 us or more)",
            t.rows
        );
        // The check covers thrust: the hold-down fires in every period of its 10 s, for
        // at least one 20 ms minimum on-time (measured: 817 steps or more).
        assert!(
            thrust_rows > 100,
            "sample {sample}: {thrust_rows} rows under thrust"
        );
        assert!(
            flight_rows > 100,
            "sample {sample}: {flight_rows} rows in flight"
        );
    }
}

/// `descent.toml` cut to 40 s: the law brakes the lander from 15 m and it is still
/// descending under thrust when the run ends (unbraked it would land after 32 s, so the
/// scenario is accepted; braked to its profile it needs more than a minute).
fn descent_in_flight() -> String {
    shipped("descent").replace("t_max_s = 150.0", "t_max_s = 40.0")
}

#[test]
fn sweep_peaks_are_the_specific_force_under_thrust() {
    // A lander braked by its descent law for the whole run touches nothing: the specific
    // force is the thrust alone, so its peak is the largest |thrust| / m over the steps,
    // and along Z_B the largest |thrust_b_z| / m. The sweep's peak columns (the kernel)
    // against the trace of the same sample (the reference, every step): the same
    // firings act on both (thrust is piecewise constant, quantised to minimum on-times),
    // so the peaks agree to a rounding of the rotation and the quotient (1e-12 relative).
    // Before thrust was counted, both peaks were 0. The lander is airborne at t_max with
    // its loop powered: `bouncing`, not `held`.
    let dir = TempDir::new("sweep_peaks_are_the_specific_force_under_thrust");
    let text = descent_in_flight();
    let mass = Scenario::from_toml(&text).unwrap().lander.mass_kg;
    let file = dir.write("descent-40.toml", &text);
    let file = file.to_str().unwrap();
    let samples = 6;
    // (It warns that no sample touched the surface: that is the point.)
    let run = touchdown(
        dir.path(),
        &[
            "sweep",
            "--scenario",
            file,
            "--samples",
            "6",
            "--out",
            "s.arrow",
            "--quiet",
        ],
    );
    assert_eq!(run.code, Some(0), "{run}");
    let sweep = read(&dir.join("s.arrow"));
    for i in 0..samples {
        let out = format!("t{i}.arrow");
        let index = i.to_string();
        touchdown(
            dir.path(),
            &[
                "trace", "--sweep", "s.arrow", "--sample", &index, "--out", &out,
            ],
        )
        .assert_ok();
        let t = read(&dir.join(&out));
        let (mut peak, mut peak_z) = (0.0f64, 0.0f64);
        for r in 0..t.rows {
            if t.columns["dt_s"][r] > 0.0 {
                let thrust = vector(&t, THRUST, r);
                peak = peak.max(norm(thrust) / mass);
                peak_z = peak_z.max(thrust[2].abs() / mass);
            }
        }
        let (kernel, kernel_z) = (
            sweep.columns["peak_acceleration_m_s2"][i],
            sweep.columns["peak_acceleration_z_body_m_s2"][i],
        );
        println!(
            "sample {i}: peak {kernel:.9} m/s^2 (thrust / m {peak:.9}), along Z_B \
             {kernel_z:.9} ({peak_z:.9})"
        );
        assert!(peak > 0.0, "sample {i}: no thrust in the trace");
        assert!(
            (kernel - peak).abs() <= 1e-12 * peak,
            "sample {i}: the sweep's peak acceleration {kernel} against |thrust| / m {peak}"
        );
        assert!(
            (kernel_z - peak_z).abs() <= 1e-12 * peak_z,
            "sample {i}: the sweep's peak along Z_B {kernel_z} against |thrust_b_z| / m {peak_z}"
        );
        assert!(
            sweep.columns["first_contact_s"][i].is_nan(),
            "sample {i} touched the surface"
        );
        assert_eq!(
            touchdown::reference::Outcome::ALL[usize::from(sweep.outcome[i])],
            touchdown::reference::Outcome::Bouncing,
            "sample {i}: airborne at t_max with its loop powered"
        );
    }
}
