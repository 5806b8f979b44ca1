//! Rows against traces: sweep rows hold the inputs and outcomes of `touchdown trace` of
//! their samples, traced from the scenario and seed and from the sweep file alone.

use super::{ROUGH, SweepFile, check_sweep_file, read_sweep, sweep};
use crate::common::{Run, SHORT, TempDir, touchdown};
use std::collections::BTreeSet;
use touchdown::reference::Outcome;
use touchdown::scenario::INPUT_FIELDS;

/// The `terrain_tile N (offset U m, V m)` line of a trace's printout, as printed.
fn trace_terrain(run: &Run) -> Option<(u32, String, String)> {
    let line = run
        .stdout
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("terrain_tile "))?;
    let parse = || -> Option<(u32, String, String)> {
        let (tile, rest) = line.trim_start().split_once(" (offset ")?;
        let (u, v) = rest.strip_suffix(" m)")?.split_once(" m, ")?;
        Some((tile.parse().ok()?, u.to_string(), v.to_string()))
    };
    Some(parse().unwrap_or_else(|| panic!("cannot read the terrain line {line:?} of {run}")))
}

/// Checks that sweep rows hold the inputs and the outcome of `touchdown trace --sample i`
/// with the flags `source` (`--scenario F --seed S`, or `--sweep FILE`), and that the trace
/// stores the scenario text the sweep stored (seed included).
fn check_rows_against_traces(dir: &TempDir, source: &[&str], seed: &str, file: &SweepFile) {
    let rows = file.rows() as u64;
    let outcomes = file.strings("outcome");
    // The first samples, the last one, and the first of every outcome that occurs.
    let mut indices: BTreeSet<u64> = [0, 1, 2, rows - 1].into();
    for o in Outcome::ALL {
        if let Some(i) = outcomes.iter().position(|x| x == o.name()) {
            indices.insert(i as u64);
        }
    }
    let sample_seeds = file.u64s("sample_seed");
    let tiles = file.u32s("terrain_tile");
    let (offset_u, offset_v) = (
        file.f64s("terrain_offset_u_m"),
        file.f64s("terrain_offset_v_m"),
    );
    let inputs: Vec<Vec<f64>> = INPUT_FIELDS.iter().map(|(n, _)| file.f64s(n)).collect();

    let mut failures = Vec::new();
    for i in indices {
        let k = i as usize;
        let index = i.to_string();
        let out = format!("trace-{i}.arrow");
        let args = [
            &["trace"],
            source,
            &["--sample", &index, "--every", "1e9", "--out", &out],
        ]
        .concat();
        let run = touchdown(dir.path(), &args);
        run.assert_ok();
        let trace = read_sweep(&dir.join(&out)); // an Arrow IPC file too
        let meta = |key: &str| {
            trace
                .meta(key)
                .unwrap_or_else(|| panic!("trace {i} has no {key}"))
                .to_string()
        };
        let mut problems = Vec::new();
        if meta("touchdown.sample") != index || meta("touchdown.seed") != seed {
            problems.push(format!(
                "trace of sample {} of seed {}",
                meta("touchdown.sample"),
                meta("touchdown.seed")
            ));
        }
        if meta("touchdown.sample_seed") != sample_seeds[k].to_string() {
            problems.push(format!(
                "sample_seed: row {}, trace {}",
                sample_seeds[k],
                meta("touchdown.sample_seed")
            ));
        }
        for ((name, _), column) in INPUT_FIELDS.iter().zip(&inputs) {
            let text = meta(&format!("touchdown.input.{name}"));
            let traced: f64 = text
                .parse()
                .unwrap_or_else(|_| panic!("trace {i}: {name} = {text:?} is not a number"));
            if traced.to_bits() != column[k].to_bits() {
                problems.push(format!("{name}: row {:?}, trace {traced:?}", column[k]));
            }
        }
        if trace.meta("touchdown.scenario") != file.meta("touchdown.scenario") {
            problems.push(format!(
                "scenario text: sweep {:?}, trace {:?}",
                file.meta("touchdown.scenario"),
                trace.meta("touchdown.scenario")
            ));
        }
        if meta("touchdown.outcome") != outcomes[k] {
            problems.push(format!(
                "outcome: row (kernel) {}, trace (reference) {}",
                outcomes[k],
                meta("touchdown.outcome")
            ));
        }
        // The trace prints the terrain tile and offsets (to the mm) on rough terrain only.
        let row_terrain = (
            tiles[k],
            format!("{:.3}", offset_u[k]),
            format!("{:.3}", offset_v[k]),
        );
        match trace_terrain(&run) {
            Some(t) if t != row_terrain => {
                problems.push(format!("terrain: row {row_terrain:?}, trace {t:?}"));
            }
            None if (tiles[k], offset_u[k], offset_v[k]) != (0, 0.0, 0.0) => {
                problems.push(format!("terrain: row {row_terrain:?} on a flat surface"));
            }
            _ => {}
        }
        if !problems.is_empty() {
            failures.push(format!(
                "sample {i}:\n    {}\n{run}",
                problems.join("\n    ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "rows of the sweep (seed {seed}) differ from their traces `touchdown trace {}`:\n\n{}",
        source.join(" "),
        failures.join("\n\n")
    );
}

#[test]
fn rows_hold_the_inputs_and_outcomes_of_their_traces() {
    let dir = TempDir::new("sweep-vs-trace");
    for (name, text, seed, samples) in [
        ("short.toml", SHORT, "5", "3000"),
        ("rough.toml", ROUGH, "9", "2000"),
    ] {
        dir.write(name, text);
        let out = format!("{name}.arrow");
        let (_, s) = sweep(
            &dir,
            &[
                "--scenario",
                name,
                "--seed",
                seed,
                "--samples",
                samples,
                "--out",
                &out,
            ],
        );
        let file = check_sweep_file(&dir.join(&out), &s, seed.parse().unwrap(), text);
        // Traced from the scenario and seed, and from the sweep file alone.
        check_rows_against_traces(&dir, &["--scenario", name, "--seed", seed], seed, &file);
        check_rows_against_traces(&dir, &["--sweep", &out], seed, &file);
    }
}

#[test]
fn touchdown_state_columns_are_the_traces_first_contact() {
    // The sweep's touchdown-state columns (the kernels) against the trace of the same
    // sample (the reference, every step): the first row whose footpads touch holds the
    // state at the start of the first contact's step, from which the speeds towards and
    // along the surface (whose normal n and downhill u the sample's slope and azimuth
    // give), the tilt and the rates follow. Kernel and reference may place that step one
    // step (1 ms) apart: the speeds agree within gravity over it, 0.0168 x 1e-3 m/s, and
    // rounding (1e-5 m/s), the tilt within 5e-3 deg, the rates within 1e-3 deg/s. Every
    // sample of the default sweep touches, so no column is null.
    let dir = TempDir::new("touchdown-state-vs-trace");
    let samples = 6;
    let (_, _) = sweep(&dir, &["--samples", "6", "--out", "s.arrow"]);
    let file = read_sweep(&dir.join("s.arrow"));
    let column = |name: &str| file.f64s(name);
    let (normal, along, tilt) = (
        column("touchdown_normal_speed_m_s"),
        column("touchdown_tangential_speed_m_s"),
        column("touchdown_tilt_deg"),
    );
    let rates = ["x", "y", "z"].map(|a| column(&format!("touchdown_rate_{a}_deg_s")));
    for i in 0..samples {
        let out = format!("t{i}.arrow");
        touchdown(
            dir.path(),
            &[
                "trace",
                "--sweep",
                "s.arrow",
                "--sample",
                &i.to_string(),
                "--out",
                &out,
            ],
        )
        .assert_ok();
        let t = read_sweep(&dir.join(&out));
        let input = |name: &str| -> f64 {
            t.meta(&format!("touchdown.input.{name}"))
                .unwrap()
                .parse()
                .unwrap()
        };
        let (a, b) = (
            input("slope_deg").to_radians(),
            input("downhill_azimuth_deg").to_radians(),
        );
        let n = [a.sin() * b.cos(), a.sin() * b.sin(), a.cos()];
        let legs: Vec<Vec<f64>> = (0..4)
            .map(|l| t.f64s(&format!("leg{l}_penetration_m")))
            .collect();
        let row = (0..t.rows())
            .find(|&r| legs.iter().any(|l| l[r] > 0.0))
            .expect("the sample touches");
        let v = ["vx_m_s", "vy_m_s", "vz_m_s"].map(|c| t.f64s(c)[row]);
        let towards = -(0..3).map(|k| n[k] * v[k]).sum::<f64>();
        let speed = (0..3).map(|k| v[k] * v[k]).sum::<f64>().sqrt();
        let on_plane = (speed * speed - towards * towards).max(0.0).sqrt();
        let [w, x, y, z] = ["qw", "qx", "qy", "qz"].map(|c| t.f64s(c)[row]);
        let z_body = [
            2.0 * (x * z + w * y),
            2.0 * (y * z - w * x),
            1.0 - 2.0 * (x * x + y * y),
        ];
        let traced_tilt = (0..3)
            .map(|k| z_body[k] * n[k])
            .sum::<f64>()
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        let speeds = 0.0168e-3 + 1e-5;
        let case = format!("sample {i} (trace row {row})");
        assert!(
            (normal[i] - towards).abs() <= speeds,
            "{case}: towards {} vs {towards}",
            normal[i]
        );
        assert!(
            (along[i] - on_plane).abs() <= speeds,
            "{case}: along {} vs {on_plane}",
            along[i]
        );
        assert!(
            (tilt[i] - traced_tilt).abs() <= 5e-3,
            "{case}: tilt {} vs {traced_tilt}",
            tilt[i]
        );
        for (k, c) in ["rate_x_deg_s", "rate_y_deg_s", "rate_z_deg_s"]
            .iter()
            .enumerate()
        {
            let traced = t.f64s(c)[row];
            assert!(
                (rates[k][i] - traced).abs() <= 1e-3,
                "{case}: {c} {} vs {traced}",
                rates[k][i]
            );
        }
    }
}
